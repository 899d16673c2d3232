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
#include "dermis/sss/pointcloud/point_cloud_io.h"
#include "dermis/sss/pointcloud/point_distribution.h"

namespace dermis {

namespace pc = sss::pointcloud;

namespace {

// The object's surface as one triangle list (spheres tessellated), in world space,
// wound so that cross(p1 - p0, p2 - p0) points out of the object.
void object_triangles(const RenderScene& sc, const std::vector<int>& shapes, std::vector<Vec3>& positions,
                      std::vector<uint32_t>& indices) {
  for (int i : shapes) {
    const Shape& shape = sc.shapes[i];
    std::vector<Vec3> p = shape.positions;
    std::vector<uint32_t> t = shape.indices;
    if (shape.type == Shape::Type::Sphere) {
      tessellate_sphere(shape.radius, 96, p, t);
      for (Vec3& v : p) v += shape.center;
    }
    const uint32_t base = uint32_t(positions.size());
    positions.insert(positions.end(), p.begin(), p.end());
    for (std::size_t j = 0; j + 2 < t.size(); j += 3) {
      const bool flip = shape.flip_normals;
      indices.insert(indices.end(), {base + t[j], base + t[flip ? j + 2 : j + 1], base + t[flip ? j + 1 : j + 2]});
    }
  }
}

}  // namespace

PointCloudReport build_point_clouds(RenderScene& sc, const PointCloudOptions& options, Progress::Style style,
                                    const std::atomic<bool>* cancel, ProcessGroup* group_or_null) {
  using Clock = std::chrono::steady_clock;
  ProcessGroup& group = group_or_null ? *group_or_null : single_process();
  PointCloudReport report;
  // The point-cloud objects, in order of their first shape.
  std::map<int, std::vector<int>> objects;
  for (std::size_t i = 0; i < sc.shapes.size(); ++i) {
    const Material& mat = sc.materials[sc.shapes[i].material];
    if (mat.type != Material::Type::Subsurface) continue;
    if (!std::holds_alternative<PointCloudMethod>(sc.subsurface[mat.subsurface]->method)) continue;
    if (sc.shapes[i].instance >= 0)
      throw std::runtime_error("subsurface method \"pointcloud\": objects inside ObjectBegin/ObjectInstance are not "
                               "supported; use another method for instanced objects");
    objects[sc.object_of_shape[i]].push_back(int(i));
  }
  if (objects.empty()) {
    // Said rather than ignored: a wrong scene or a misspelt method would otherwise pass unseen.
    for (const auto& [option, path] : {std::pair{"--load-pointcloud", &options.load_path},
                                       std::pair{"--save-pointcloud", &options.save_path}})
      if (!path->empty())
        report.warnings.push_back(fmt::format("warning: {} {}: the scene has no object whose subsurface method is "
                                              "\"pointcloud\"; no point cloud was {}",
                                              option, *path, option[2] == 'l' ? "read" : "written"));
    return report;
  }
  int k = 0;
  for (const auto& [object, shapes] : objects) {
    const Material& mat = sc.materials[sc.shapes[shapes[0]].material];
    const SubsurfaceMaterial& material = *sc.subsurface[mat.subsurface];
    auto& m = std::get<PointCloudMethod>(sc.subsurface[mat.subsurface]->method);
    // Light enters through the boundary: smooth (1 - Fr), or the rough one's T.
    const RoughExitTable* rough = material.exit_table ? &*material.exit_table : nullptr;
    const SubsurfaceParams& params = m.params();
    const std::string suffix = k == 0 ? "" : fmt::format(".{}", k);
    ++k;
    auto t0 = Clock::now();
    pc::PointCloud cloud;
    if (!options.load_path.empty()) {
      cloud = pc::load_point_cloud(options.load_path + suffix);
    } else {
      std::vector<Vec3> positions;
      std::vector<uint32_t> indices;
      object_triangles(sc, shapes, positions, indices);
      double area = pc::mesh_area(positions, indices);
      std::size_t count = options.points;
      if (count == 0) {
        // Points per mfp^2 (pointdensity) up to the budget (maxpoints): the density alone
        // grows without bound with area / mfp^2.
        const double mfp = m.min_mean_free_path();
        const double wanted = pc::point_count_for_density(area, mfp, params.point_density);
        count = std::size_t(std::min(wanted, double(params.max_points)));
        if (wanted > double(params.max_points))
          report.warnings.push_back(fmt::format(
              "{}: warning: point cloud of object {}: \"pointdensity\" {} asks for {:.3g} points (area {:.3g}, mfp {:.3g}); "
              "using the \"maxpoints\" budget of {} (spacing {:.3g} instead of {:.3g}). Raise \"maxpoints\" or "
              "--points for a finer cloud",
              params.loc.str(), k, params.point_density, wanted, area, mfp, params.max_points,
              std::sqrt(area / double(count)), mfp / std::sqrt(params.point_density)));
      }
      count = std::max<std::size_t>(count, 16);
      {
        // The blue-noise distribution (seconds for 10^5 points, single-threaded) shows its
        // progress and stops on Ctrl-C. Alone, the process stops at once; in a group every
        // process finishes it and they stop together after the irradiance loop below.
        pc::DistributionOptions dist;
        Progress placing(fmt::format("Point cloud {}: placing {} points", k, count),
                         int64_t(pc::distribution_steps(count, dist)), style);
        std::size_t reported = 0;
        dist.progress = [&](std::size_t done) {
          if (cancel && cancel->load(std::memory_order_relaxed) && group.size() == 1) throw Interrupted();
          placing.advance(int64_t(done - reported));
          reported = done;
        };
        cloud.points = pc::distribute_points(positions, indices, count, mix64(options.seed ^ (0x9e37 + object)), dist);
        placing.finish();
      }
      cloud.irradiance.resize(cloud.points.size());
      const int samples = params.irradiance_samples;
      const int outside_medium = sc.shapes[shapes[0]].outside_medium;
      Progress progress(fmt::format("Point cloud {} ({} points)", k, cloud.points.size()),
                        int64_t(cloud.points.size()), style);
      const auto [begin, end] = group.share(cloud.points.size());
      tbb::parallel_for(begin, end, [&](std::size_t j) {
        if (cancel && cancel->load(std::memory_order_relaxed)) return;
        PathCounters counters;
        const pc::SurfacePoint& p = cloud.points[j];
        RGB sum(0);
        for (int s = 0; s < samples; ++s) {
          // Each point is a "pixel" of the sampler: its irradiance samples are stratified.
          Sampler sampler(options.sampler, options.seed, 0x70c10d00000000ull + (uint64_t(object) << 32) + j,
                          uint32_t(s));
          RGB e = transmitted_irradiance(sc, p.position, p.normal, params.eta, outside_medium, sampler, counters,
                                         rough);
          if (e.is_finite()) sum += e;
        }
        cloud.irradiance[j] = sum / float(samples);
        progress.advance();
      });
      if (group.any(cancel && cancel->load())) throw Interrupted();
      static_assert(sizeof(RGB) == 3 * sizeof(float));
      group.allgather(std::span<float>(cloud.irradiance.data()->c, 3 * cloud.irradiance.size()), 3);
      progress.advance(int64_t(cloud.points.size() - (end - begin)));
      progress.finish();
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
