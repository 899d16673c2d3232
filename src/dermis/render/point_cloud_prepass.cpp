#include "dermis/render/point_cloud_prepass.h"

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "dermis/core/rng.h"
#include "dermis/geometry/sphere_tessellation.h"
#include "dermis/render/integrator.h"
#include "dermis/sss/pointcloud/illumination_detail.h"
#include "dermis/sss/pointcloud/point_cloud_io.h"
#include "dermis/sss/pointcloud/point_distribution.h"

namespace dermis {

namespace pc = sss::pointcloud;

namespace {

// A sphere of the object, traced as Embree's analytic sphere and tessellated only to
// place the points: the triangles [first, end) of the object's list.
struct TessellatedSphere {
  uint32_t first = 0, end = 0;
  Vec3 center;
  float radius = 0;
  bool flip_normals = false;
  double area_ratio = 1;  // the sphere's area over its tessellation's
};

// The object's surface as one triangle list (spheres tessellated), in world space,
// wound so that cross(p1 - p0, p2 - p0) points out of the object.
void object_triangles(const RenderScene& sc, const std::vector<int>& shapes, std::vector<Vec3>& positions,
                      std::vector<uint32_t>& indices, std::vector<TessellatedSphere>& spheres) {
  for (int i : shapes) {
    const Shape& shape = sc.shapes[i];
    std::vector<Vec3> p = shape.positions;
    std::vector<uint32_t> t = shape.indices;
    if (shape.type == Shape::Type::Sphere) {
      tessellate_sphere(shape.radius, 96, p, t);
      for (Vec3& v : p) v += shape.center;
      TessellatedSphere ts;
      ts.first = uint32_t(indices.size() / 3);
      ts.end = ts.first + uint32_t(t.size() / 3);
      ts.center = shape.center;
      ts.radius = shape.radius;
      ts.flip_normals = shape.flip_normals;
      ts.area_ratio = 4 * kPiD * double(shape.radius) * double(shape.radius) / pc::mesh_area(p, t);
      spheres.push_back(ts);
    }
    const uint32_t base = uint32_t(positions.size());
    positions.insert(positions.end(), p.begin(), p.end());
    for (std::size_t j = 0; j + 2 < t.size(); j += 3) {
      const bool flip = shape.flip_normals;
      indices.insert(indices.end(), {base + t[j], base + t[flip ? j + 2 : j + 1], base + t[flip ? j + 1 : j + 2]});
    }
  }
}

// Moves the points placed on a sphere's tessellation onto the sphere the renderer traces,
// along the radius, with the sphere's normal. On a facet a point lies inside the sphere by
// up to the facet's sagitta (5e-4 of the radius at 96 segments), more than a ray's
// offset from the surface: its irradiance rays started inside the object and were
// blocked by the sphere itself, and the cloud read dark (a uniform sky: the radiant
// exitance of a sphere of 20 mean free paths 29% low). The area shares scale to the
// sphere's area.
void project_onto_spheres(std::vector<pc::SurfacePoint>& points, const std::vector<TessellatedSphere>& spheres) {
  for (pc::SurfacePoint& p : points)
    for (const TessellatedSphere& s : spheres) {
      if (p.triangle < s.first || p.triangle >= s.end) continue;
      const Vec3 outward = normalize(p.position - s.center);
      p.position = s.center + outward * s.radius;
      p.normal = s.flip_normals ? -outward : outward;
      p.area = float(double(p.area) * s.area_ratio);
      break;
    }
}

// The point-cloud objects, in order of their first shape: each with its shapes.
std::map<int, std::vector<int>> point_cloud_objects(const RenderScene& sc) {
  std::map<int, std::vector<int>> objects;
  for (std::size_t i = 0; i < sc.shapes.size(); ++i) {
    const Material& mat = sc.materials[sc.shapes[i].material];
    if (mat.type != Material::Type::Subsurface) continue;
    if (!std::holds_alternative<PointCloudMethod>(sc.subsurface[mat.subsurface]->method)) continue;
    if (sc.shapes[i].instance >= 0)
      throw std::runtime_error(
          "subsurface method \"pointcloud\": objects inside ObjectBegin/ObjectInstance are not "
          "supported; use another method for instanced objects");
    objects[sc.object_of_shape[i]].push_back(int(i));
  }
  return objects;
}

// Said rather than ignored: a wrong scene or a misspelt method would otherwise pass unseen.
void warn_of_unused_cloud_files(const PointCloudOptions& options, PointCloudReport& report) {
  for (const auto& [option, path] :
       {std::pair{"--load-pointcloud", &options.load_path}, std::pair{"--save-pointcloud", &options.save_path}})
    if (!path->empty())
      report.warnings.push_back(
          fmt::format("warning: {} {}: the scene has no object whose subsurface method is "
                      "\"pointcloud\"; no point cloud was {}",
                      option, *path, option[2] == 'l' ? "read" : "written"));
}

// One object's cloud while it is computed: its surface, where its points go, and how many.
struct CloudJob {
  const RenderScene& sc;
  const PointCloudOptions& options;
  Progress::Style style;
  const std::atomic<bool>* cancel;
  ProcessGroup& group;
  int object = 0;  // the subsurface object
  int number = 0;  // 1, 2, ...: the cloud's number in messages
  const PointCloudMethod& method;
  const RoughExitTable* rough = nullptr;
  int outside_medium = -1;
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<TessellatedSphere> spheres;
};

// The count: --points as given; else, with the local disk, the smallest cloud that
// represents the illumination (seed 001: the local disk integral frees the cloud from the
// profile's falloff, so it only has to sample E): a pilot, refined until the leave-one-out
// miss of E is within "illuminationerror", up to the budget ("maxpoints") and the
// profile's density ("pointdensity" per mfp^2: detail finer than that is blurred by the
// profile). Without the local disk, or with "illuminationerror" 0: the density, up to the
// budget.
struct PointCount {
  std::size_t count = 0, cap = 0;
  bool adaptive = false;  // refined round by round
  double wanted = 0;      // the profile's density's count
};

PointCount first_point_count(const CloudJob& job, double area, PointCloudReport& report) {
  const SubsurfaceParams& params = job.method.params();
  PointCount n;
  n.count = n.cap = job.options.points;
  n.adaptive = n.count == 0 && params.local_disk && params.illumination_error > 0;
  const double mfp = job.method.min_mean_free_path();
  n.wanted = pc::point_count_for_density(area, mfp, params.point_density);
  if (n.count == 0) {
    n.cap = std::max<std::size_t>(16, std::size_t(std::min(n.wanted, double(params.max_points))));
    n.count = n.adaptive ? pc::pilot_point_count(n.cap) : n.cap;
    if (!n.adaptive && n.wanted > double(params.max_points))
      report.warnings.push_back(fmt::format(
          "{}: warning: point cloud of object {}: \"pointdensity\" {} asks for {:.3g} points (area {:.3g}, mfp "
          "{:.3g}); "
          "using the \"maxpoints\" budget of {} (spacing {:.3g} instead of {:.3g}). Raise \"maxpoints\" or "
          "--points for a finer cloud",
          params.loc.str(), job.number, params.point_density, n.wanted, area, mfp, params.max_points,
          std::sqrt(area / double(n.cap)), mfp / std::sqrt(params.point_density)));
  }
  n.count = std::max<std::size_t>(n.count, 16);
  return n;
}

// The blue-noise distribution (seconds for 10^5 points, single-threaded) shows its
// progress and stops on Ctrl-C. Alone, the process stops at once; in a group every
// process finishes it and they stop together after the irradiance loop.
std::vector<pc::SurfacePoint> place_points(const CloudJob& job, std::size_t count) {
  pc::DistributionOptions dist;
  Progress placing(fmt::format("Point cloud {}: placing {} points", job.number, count),
                   int64_t(pc::distribution_steps(count, dist)), job.style);
  std::size_t reported = 0;
  dist.progress = [&](std::size_t done) {
    if (job.cancel && job.cancel->load(std::memory_order_relaxed) && job.group.size() == 1) throw Interrupted();
    placing.advance(int64_t(done - reported));
    reported = done;
  };
  std::vector<pc::SurfacePoint> points =
      pc::distribute_points(job.positions, job.indices, count, mix64(job.options.seed ^ (0x9e37 + job.object)), dist);
  project_onto_spheres(points, job.spheres);
  placing.finish();
  return points;
}

// The irradiance transmitted into the object at each point, and the variance of each
// point's luminance estimate (the refinement's noise); the group shares the points.
void estimate_irradiance(const CloudJob& job, pc::PointCloud& cloud, std::vector<float>& variance) {
  const int samples = job.method.params().irradiance_samples;
  const float eta = job.method.params().eta;
  cloud.irradiance.assign(cloud.points.size(), RGB(0));
  variance.assign(cloud.points.size(), 0.0f);
  Progress progress(fmt::format("Point cloud {} ({} points)", job.number, cloud.points.size()),
                    int64_t(cloud.points.size()), job.style);
  const auto [begin, end] = job.group.share(cloud.points.size());
  tbb::parallel_for(begin, end, [&](std::size_t j) {
    if (job.cancel && job.cancel->load(std::memory_order_relaxed)) return;
    PathCounters counters;
    const pc::SurfacePoint& p = cloud.points[j];
    // Two halves, each its own scrambled low-discrepancy set (a different sampler
    // "pixel"): their difference is an unbiased estimate of the noise of their mean,
    // which the refinement needs (the spread of stratified samples is not: it
    // overstates their mean's noise). One sample: one half, the noise unknown (taken
    // as 0, so that it counts as detail and the cloud grows rather than stops short).
    const int halves = samples > 1 ? 2 : 1, per_half = (samples + 1) / 2;
    RGB half_sum[2] = {RGB(0), RGB(0)};
    for (int h = 0; h < halves; ++h)
      for (int s = 0; s < per_half; ++s) {
        Sampler sampler(job.options.sampler, job.options.seed,
                        0x70c10d00000000ull + (uint64_t(job.object) << 32) + (uint64_t(h) << 31) + j, uint32_t(s));
        RGB e =
            transmitted_irradiance(job.sc, p.position, p.normal, eta, job.outside_medium, sampler, counters, job.rough);
        if (e.is_finite()) half_sum[h] += e;
      }
    const RGB a = half_sum[0] / float(per_half), b = half_sum[1] / float(per_half);
    cloud.irradiance[j] = halves == 2 ? (a + b) * 0.5f : a;
    const float d = a.luminance() - b.luminance();
    if (halves == 2) variance[j] = d * d / 4;  // Var((a + b) / 2) = (Var a + Var b) / 4 = E[(a - b)^2] / 4
    progress.advance();
  });
  if (job.group.any(job.cancel && job.cancel->load())) throw Interrupted();
  static_assert(sizeof(RGB) == 3 * sizeof(float));
  job.group.allgather(std::span<float>(cloud.irradiance.data()->c, 3 * cloud.irradiance.size()), 3);
  job.group.allgather(std::span<float>(variance), 1);
  progress.advance(int64_t(cloud.points.size() - (end - begin)));
  progress.finish();
}

// One object's cloud: placed and lit, then (adaptive) refined until it represents the
// illumination.
pc::PointCloud compute_point_cloud(CloudJob& job, PointCloudReport& report) {
  const SubsurfaceParams& params = job.method.params();
  PointCount n = first_point_count(job, pc::mesh_area(job.positions, job.indices), report);
  pc::PointCloud cloud;
  std::vector<float> variance;
  std::string rounds;  // each refinement round's count and miss, for the report
  for (;;) {
    cloud.points = place_points(job, n.count);
    estimate_irradiance(job, cloud, variance);
    if (!n.adaptive) return cloud;
    // Every process holds every point's values here, so all make the same choice.
    std::vector<float> luminance(cloud.points.size());
    for (std::size_t j = 0; j < luminance.size(); ++j) luminance[j] = cloud.irradiance[j].luminance();
    const pc::IlluminationDetail detail = pc::illumination_detail(cloud.points, luminance, variance);
    const double error = detail.relative_error();
    const std::size_t next = pc::next_point_count(n.count, error, params.illumination_error, n.cap);
    rounds += fmt::format("{}{} points: {:.2g}%", rounds.empty() ? "" : ", ", n.count, 100 * error);
    if (next == n.count) {
      const std::string what = fmt::format(
          "point cloud of object {}: {} points represent the illumination to {:.2g}% (\"illuminationerror\" {:.2g}%; "
          "the leave-one-out miss of E, noise removed, by round: {}; budget {}, the profile's density {:.3g})",
          job.number, n.count, 100 * error, 100 * params.illumination_error, rounds, params.max_points, n.wanted);
      if (error > params.illumination_error && n.cap == std::size_t(params.max_points))
        report.warnings.push_back(fmt::format(
            "{}: warning: {}: the cloud is coarser than the illumination needs (the \"maxpoints\" budget stops it); "
            "raise \"maxpoints\" or --points for a finer cloud",
            params.loc.str(), what));
      else
        report.notes.push_back(what);
      return cloud;
    }
    n.count = next;
  }
}

}  // namespace

PointCloudReport build_point_clouds(RenderScene& sc, const PointCloudOptions& options, Progress::Style style,
                                    const std::atomic<bool>* cancel, ProcessGroup* group_or_null) {
  using Clock = std::chrono::steady_clock;
  ProcessGroup& group = group_or_null ? *group_or_null : single_process();
  PointCloudReport report;
  const std::map<int, std::vector<int>> objects = point_cloud_objects(sc);
  if (objects.empty()) {
    warn_of_unused_cloud_files(options, report);
    return report;
  }
  int k = 0;
  for (const auto& [object, shapes] : objects) {
    const Material& mat = sc.materials[sc.shapes[shapes[0]].material];
    const SubsurfaceMaterial& material = *sc.subsurface[mat.subsurface];
    auto& m = std::get<PointCloudMethod>(sc.subsurface[mat.subsurface]->method);
    const SubsurfaceParams& params = m.params();
    const std::string suffix = k == 0 ? "" : fmt::format(".{}", k);
    ++k;
    auto t0 = Clock::now();
    pc::PointCloud cloud;
    if (!options.load_path.empty()) {
      cloud = pc::load_point_cloud(options.load_path + suffix);
    } else {
      // Light enters through the boundary: smooth (1 - Fr), or the rough one's T.
      const RoughExitTable* rough = material.exit_table ? &*material.exit_table : nullptr;
      CloudJob job{sc, options, style, cancel, group, object, k, m, rough, sc.shapes[shapes[0]].outside_medium,
                   {}, {},      {}};
      object_triangles(sc, shapes, job.positions, job.indices, job.spheres);
      cloud = compute_point_cloud(job, report);
    }
    report.prepass_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    if (!options.save_path.empty() && group.is_root()) {
      pc::save_point_cloud(options.save_path + suffix, cloud);
      report.file_bytes += std::filesystem::file_size(options.save_path + suffix);
    }
    pc::DiffusionOptions d;
    d.epsilon = params.epsilon;
    d.local_disk = params.local_disk;
    auto diffusion = std::make_shared<pc::PointCloudDiffusion>(cloud.points, cloud.irradiance, m.profile(), d);
    const auto& st = diffusion->stats();
    report.clouds += 1;
    report.points += st.point_count;
    report.memory_bytes += st.memory_bytes;
    report.build_seconds += st.build_seconds;
    m.set_cloud(object, std::move(diffusion));
  }
  return report;
}

}  // namespace dermis
