#include "dermis/scene/loop_subdivision.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace dermis {

namespace {

// Edges, and each vertex's neighbours in fan order (Loop's "1-ring").
struct Topology {
  struct Edge {
    uint32_t v[2];
    int opposite[2] = {-1, -1};  // the third vertex of each adjacent triangle
  };
  std::vector<Edge> edges;
  std::vector<uint32_t> face_edges;  // per triangle: edges (i0,i1), (i1,i2), (i2,i0)
  // Per vertex: the neighbours in order around it (the triangles' winding); for a
  // boundary vertex the first and last are its two boundary neighbours.
  std::vector<std::vector<uint32_t>> ring;
  std::vector<char> boundary;
};

// The part [from, to] of a caller's pass that one loop of `steps` iterations is:
// reports (from + (to - from) i / steps) to the progress every kLoopCheckEvery steps.
class PassPart {
 public:
  PassPart(const LoopProgress& progress, double from, double to, std::size_t steps)
      : progress_(progress), from_(from), to_(to), steps_(steps) {}
  void at(std::size_t i) const {
    if (progress_ && i % kLoopCheckEvery == 0)
      progress_(from_ + (to_ - from_) * double(i) / double(std::max<std::size_t>(steps_, 1)));
  }

 private:
  const LoopProgress& progress_;
  double from_, to_;
  std::size_t steps_;
};

uint64_t edge_key(uint32_t a, uint32_t b) { return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a; }

// Reports its triangles over [from, (from + to) / 2] of the progress, its vertices over
// the rest.
Topology build_topology(const LoopMesh& m, const LoopProgress& progress, double from, double to) {
  const std::size_t nv = m.positions.size(), nf = m.indices.size() / 3;
  Topology t;
  t.face_edges.resize(3 * nf);
  std::unordered_map<uint64_t, uint32_t> edge_of;
  edge_of.reserve(3 * nf);
  std::vector<std::vector<uint32_t>> faces_of(nv);
  const double mid = (from + to) / 2;
  const PassPart faces_part(progress, from, mid, nf), vertices_part(progress, mid, to, nv);
  for (std::size_t f = 0; f < nf; ++f) {
    faces_part.at(f);
    const uint32_t* tri = &m.indices[3 * f];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
      throw std::invalid_argument(fmt::format("triangle {} repeats a vertex ({} {} {})", f, tri[0], tri[1], tri[2]));
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[k], b = tri[(k + 1) % 3];
      auto [it, added] = edge_of.try_emplace(edge_key(a, b), uint32_t(t.edges.size()));
      if (added) t.edges.push_back({{a, b}});
      Topology::Edge& e = t.edges[it->second];
      const int side = e.v[0] == a ? 0 : 1;  // side 0: the triangle that runs a -> b as the edge's first one did
      if (e.opposite[side] >= 0)
        throw std::invalid_argument(fmt::format(
            "edge {}-{} is used by more than two triangles or by two triangles of opposite orientation (triangle {})",
            a, b, f));
      e.opposite[side] = int(tri[(k + 2) % 3]);
      t.face_edges[3 * f + k] = it->second;
      faces_of[a].push_back(uint32_t(f));
    }
  }
  t.boundary.assign(nv, 0);
  for (const Topology::Edge& e : t.edges)
    if (e.opposite[0] < 0 || e.opposite[1] < 0) t.boundary[e.v[0]] = t.boundary[e.v[1]] = 1;

  // Fans: in a triangle (v, next, prev) the fan continues with the triangle whose `next`
  // is this one's `prev`. A boundary fan starts at the triangle whose `next` no other
  // triangle of the fan has as its `prev`.
  t.ring.resize(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    vertices_part.at(v);
    const std::vector<uint32_t>& fs = faces_of[v];
    if (fs.empty()) continue;
    auto next_prev = [&](uint32_t f, uint32_t& next, uint32_t& prev) {
      const uint32_t* tri = &m.indices[3 * std::size_t(f)];
      const int k = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
      next = tri[(k + 1) % 3];
      prev = tri[(k + 2) % 3];
    };
    std::size_t start = 0;
    if (t.boundary[v]) {
      int starts = 0;
      for (std::size_t i = 0; i < fs.size(); ++i) {
        uint32_t n, p;
        next_prev(fs[i], n, p);
        bool preceded = false;
        for (uint32_t g : fs) {
          uint32_t n2, p2;
          next_prev(g, n2, p2);
          preceded |= p2 == n;
        }
        if (!preceded) start = i, ++starts;
      }
      if (starts != 1)
        throw std::invalid_argument(
            fmt::format("vertex {} is where {} separate fans of triangles meet (not a manifold)", v, starts));
    }
    std::vector<uint32_t>& r = t.ring[v];
    uint32_t n, p;
    next_prev(fs[start], n, p);
    r.push_back(n);
    for (std::size_t used = 1;; ++used) {
      r.push_back(p);
      if (used == fs.size()) break;
      bool found = false;
      for (uint32_t g : fs) {
        uint32_t n2, p2;
        next_prev(g, n2, p2);
        if (n2 == p) {
          p = p2;
          found = true;
          break;
        }
      }
      if (!found) break;
    }
    if (!t.boundary[v]) {
      if (r.back() != r.front() || r.size() != fs.size() + 1)
        throw std::invalid_argument(
            fmt::format("vertex {} is where separate fans of triangles meet (not a manifold)", v));
      r.pop_back();  // the closed fan came back to its first neighbour
    } else if (r.size() != fs.size() + 1) {
      throw std::invalid_argument(
          fmt::format("vertex {} is where separate fans of triangles meet (not a manifold)", v));
    }
  }
  return t;
}

// Loop 1987, eq. (3.1): beta(n) = (1/n) (5/8 - (3/8 + 1/4 cos(2 pi / n))^2).
double loop_beta(std::size_t n) {
  const double c = 0.375 + 0.25 * std::cos(2 * kPiD / double(n));
  return (0.625 - c * c) / double(n);
}

}  // namespace

LoopMesh loop_refine(const LoopMesh& m, const LoopProgress& progress) {
  // The topology is most of the work: 0.8 of the pass; the new points and triangles the rest.
  const Topology t = build_topology(m, progress, 0, 0.8);
  const std::size_t nv = m.positions.size(), nf = m.indices.size() / 3;
  const PassPart vertices_part(progress, 0.8, 0.85, nv), edges_part(progress, 0.85, 0.9, t.edges.size()),
      faces_part(progress, 0.9, 1, nf);
  LoopMesh out;
  out.positions.resize(nv + t.edges.size());
  for (std::size_t v = 0; v < nv; ++v) {
    vertices_part.at(v);
    const std::vector<uint32_t>& r = t.ring[v];
    const Vec3d p(m.positions[v]);
    Vec3d q;
    if (r.empty()) {
      q = p;  // a vertex no triangle uses
    } else if (t.boundary[v]) {
      // Boundary: the cubic B-spline's even rule, 3/4 v + 1/8 (b0 + b1) (Loop 1987; Hoppe et al. 1994).
      q = p * 0.75 + (Vec3d(m.positions[r.front()]) + Vec3d(m.positions[r.back()])) * 0.125;
    } else {
      // Interior: (1 - n beta) v + beta sum q_i (Loop 1987, eq. 3.1).
      const double beta = loop_beta(r.size());
      Vec3d sum(0, 0, 0);
      for (uint32_t j : r) sum = sum + Vec3d(m.positions[j]);
      q = p * (1 - double(r.size()) * beta) + sum * beta;
    }
    out.positions[v] = Vec3(q);
  }
  for (std::size_t e = 0; e < t.edges.size(); ++e) {
    edges_part.at(e);
    const Topology::Edge& ed = t.edges[e];
    const Vec3d a(m.positions[ed.v[0]]), b(m.positions[ed.v[1]]);
    Vec3d q;
    if (ed.opposite[0] < 0 || ed.opposite[1] < 0) {
      q = (a + b) * 0.5;  // boundary edge: the B-spline's midpoint rule
    } else {
      // Interior edge: 3/8 (a + b) + 1/8 (c + d) (Loop 1987, fig. 3.2).
      q = (a + b) * 0.375 +
          (Vec3d(m.positions[uint32_t(ed.opposite[0])]) + Vec3d(m.positions[uint32_t(ed.opposite[1])])) * 0.125;
    }
    out.positions[nv + e] = Vec3(q);
  }
  out.indices.reserve(12 * nf);
  for (std::size_t f = 0; f < nf; ++f) {
    faces_part.at(f);
    const uint32_t* tri = &m.indices[3 * f];
    const uint32_t e01 = uint32_t(nv + t.face_edges[3 * f]), e12 = uint32_t(nv + t.face_edges[3 * f + 1]),
                   e20 = uint32_t(nv + t.face_edges[3 * f + 2]);
    out.indices.insert(out.indices.end(), {tri[0], e01, e20, e01, tri[1], e12, e20, e12, tri[2], e01, e12, e20});
  }
  return out;
}

std::vector<Vec3> loop_limit_positions(const LoopMesh& m, const LoopProgress& progress) {
  const Topology t = build_topology(m, progress, 0, 0.8);
  std::vector<Vec3> out(m.positions.size());
  const PassPart vertices_part(progress, 0.8, 1, m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    vertices_part.at(v);
    const std::vector<uint32_t>& r = t.ring[v];
    const Vec3d p(m.positions[v]);
    if (r.empty()) {
      out[v] = m.positions[v];
    } else if (t.boundary[v]) {
      // The cubic B-spline's point at a knot: (b0 + 4 v + b1) / 6.
      out[v] = Vec3((Vec3d(m.positions[r.front()]) + p * 4.0 + Vec3d(m.positions[r.back()])) / 6.0);
    } else {
      // Loop 1987 (limit mask from the subdivision matrix's dominant left eigenvector):
      // (1 - n chi) v + chi sum q_i, chi = 1 / (n + 3 / (8 beta)).
      const double n = double(r.size()), chi = 1 / (n + 3 / (8 * loop_beta(r.size())));
      Vec3d sum(0, 0, 0);
      for (uint32_t j : r) sum = sum + Vec3d(m.positions[j]);
      out[v] = Vec3(p * (1 - n * chi) + sum * chi);
    }
  }
  return out;
}

std::vector<Vec3> loop_limit_normals(const LoopMesh& m, const LoopProgress& progress) {
  const Topology t = build_topology(m, progress, 0, 0.7);
  const std::size_t nv = m.positions.size();
  const PassPart faces_part(progress, 0.7, 0.8, m.indices.size() / 3), vertices_part(progress, 0.8, 1, nv);
  // The side the triangles face: the sum of their area vectors around each vertex.
  std::vector<Vec3d> facing(nv, Vec3d(0, 0, 0));
  for (std::size_t f = 0; f < m.indices.size() / 3; ++f) {
    faces_part.at(f);
    const uint32_t* tri = &m.indices[3 * f];
    const Vec3d a(m.positions[tri[0]]), b(m.positions[tri[1]]), c(m.positions[tri[2]]);
    const Vec3d n = cross(b - a, c - a);
    for (int k = 0; k < 3; ++k) facing[tri[k]] = facing[tri[k]] + n;
  }
  std::vector<Vec3> out(nv, Vec3(0, 0, 1));
  for (std::size_t v = 0; v < nv; ++v) {
    vertices_part.at(v);
    const std::vector<uint32_t>& r = t.ring[v];
    if (r.empty()) continue;
    const std::size_t n = r.size();
    auto q = [&](std::size_t i) { return Vec3d(m.positions[r[i]]); };
    const Vec3d p(m.positions[v]);
    Vec3d t1, t2;
    if (!t.boundary[v]) {
      // Loop 1987: tangents sum cos(2 pi i / n) q_i and sum sin(2 pi i / n) q_i.
      t1 = t2 = Vec3d(0, 0, 0);
      for (std::size_t i = 0; i < n; ++i) {
        const double a = 2 * kPiD * double(i) / double(n);
        t1 = t1 + q(i) * std::cos(a);
        t2 = t2 + q(i) * std::sin(a);
      }
    } else {
      // Hoppe et al. 1994, section 3.2: along the boundary b0 - b1; across it by valence.
      t1 = q(0) - q(n - 1);
      if (n == 2) {
        t2 = q(0) + q(1) - p * 2.0;
      } else if (n == 3) {
        t2 = q(1) - p;
      } else if (n == 4) {
        t2 = q(1) * 2.0 + q(2) * 2.0 - q(0) - q(3) - p * 2.0;
      } else {
        const double theta = kPiD / double(n - 1);
        t2 = (q(0) + q(n - 1)) * std::sin(theta);
        for (std::size_t i = 1; i + 1 < n; ++i)
          t2 = t2 + q(i) * ((2 * std::cos(theta) - 2) * std::sin(double(i) * theta));
      }
    }
    Vec3d nrm = cross(t1, t2);
    const double len = length(nrm);
    if (!(len > 1e-12 * std::max(length_squared(t1), length_squared(t2)))) nrm = facing[v];  // degenerate ring
    if (dot(nrm, facing[v]) < 0) nrm = -nrm;
    const double l = length(nrm);
    if (l > 0) out[v] = Vec3(nrm / l);
  }
  return out;
}

TriangleMeshDesc loop_subdivision_surface(const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                                          int levels, const LoadMonitor* monitor) {
  if (levels < 0) throw std::invalid_argument(fmt::format("levels must be at least 0, got {}", levels));
  std::size_t triangles = indices.size() / 3;
  for (int l = 0; l < levels; ++l) {
    triangles *= 4;
    if (triangles > kMaxLoopTriangles)
      throw std::invalid_argument(fmt::format("{} levels of {} triangles would make more than {} triangles", levels,
                                              indices.size() / 3, kMaxLoopTriangles));
  }
  // Progress in triangles made: each level makes 4x its input's; the limit positions
  // and normals count as one more pass over the final triangles. Inside each pass the
  // cancel flag is checked every kLoopCheckEvery triangles or vertices.
  LoadStage stage(monitor, "subdividing (loopsubdiv)");
  const double total = double(triangles) * (1 + 4.0 / 3.0);
  double made = 0, span = 0;  // the pass under way: triangles [made, made + span]
  const LoopProgress in_pass = [&](double f) { stage.update((made + f * span) / total); };
  const LoopProgress none;
  const LoopProgress& progress = monitor ? in_pass : none;
  LoopMesh m{positions, indices};
  for (int l = 0; l < levels; ++l) {
    span = 4 * double(m.indices.size() / 3);
    m = loop_refine(m, progress);
    made += span;
    stage.update(made / total);
  }
  TriangleMeshDesc out;
  span = 0.5 * double(triangles);
  out.positions = loop_limit_positions(m, progress);
  made += span;
  stage.update(made / total);
  out.normals = loop_limit_normals(m, progress);
  out.indices = std::move(m.indices);
  stage.finish();
  return out;
}

}  // namespace dermis
