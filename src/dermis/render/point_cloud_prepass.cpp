#include "dermis/render/point_cloud_prepass.h"

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "dermis/core/rng.h"
#include "dermis/render/integrator.h"
#include "dermis/render/render_scene.h"
#include "dermis/sss/pointcloud/point_cloud_io.h"
#include "dermis/sss/pointcloud/point_distribution.h"

namespace dermis {

namespace pc = sss::pointcloud;

PointCloudReport build_point_clouds(RenderScene& sc, const PointCloudOptions& options) {
  using Clock = std::chrono::steady_clock;
  PointCloudReport report;
  sc.point_clouds.clear();
  sc.point_clouds.resize(sc.shapes.size());
  int k = 0;
  for (std::size_t i = 0; i < sc.shapes.size(); ++i) {
    const Shape& shape = sc.shapes[i];
    const Material& mat = sc.materials[shape.material];
    if (mat.type != Material::Type::Subsurface) continue;
    const SubsurfaceMethod& m = *sc.subsurface[mat.subsurface];
    if (m.params.method != SubsurfaceParams::Method::PointCloud) continue;
    if (shape.instance >= 0)
      throw std::runtime_error("subsurface method \"pointcloud\": objects inside ObjectBegin/ObjectInstance are not "
                               "supported; use another method for instanced objects");
    const std::string suffix = k == 0 ? "" : fmt::format(".{}", k);
    ++k;
    auto t0 = Clock::now();
    pc::PointCloud cloud;
    if (!options.load_path.empty()) {
      cloud = pc::load_point_cloud(options.load_path + suffix);
    } else {
      std::vector<Vec3> positions = shape.positions;
      std::vector<uint32_t> indices = shape.indices;
      if (shape.type == Shape::Type::Sphere) {
        tessellate_sphere(shape.radius, 96, positions, indices);
        for (Vec3& p : positions) p += shape.center;
      }
      double area = pc::mesh_area(positions, indices);
      double mfp = std::min({m.mean_free_path[0], m.mean_free_path[1], m.mean_free_path[2]});
      std::size_t count = options.points > 0 ? options.points
                                             : pc::point_count_for_density(area, mfp, m.params.point_density);
      count = std::max<std::size_t>(count, 16);
      cloud.points = pc::distribute_points(positions, indices, count, mix64(options.seed ^ (0x9e37 + i)));
      if (shape.flip_normals)
        for (auto& p : cloud.points) p.normal = -p.normal;
      cloud.irradiance.resize(cloud.points.size());
      const int samples = m.params.irradiance_samples;
      tbb::parallel_for(std::size_t(0), cloud.points.size(), [&](std::size_t j) {
        PathCounters counters;
        const pc::SurfacePoint& p = cloud.points[j];
        RGB sum(0);
        for (int s = 0; s < samples; ++s) {
          // Each point is a "pixel" of the sampler: its irradiance samples are stratified.
          Sampler sampler(options.sampler, options.seed, 0x70c10d00000000ull + (uint64_t(i) << 32) + j, uint32_t(s));
          RGB e = transmitted_irradiance(sc, p.position, p.normal, m.params.eta, shape.outside_medium, sampler,
                                         counters);
          if (e.is_finite()) sum += e;
        }
        cloud.irradiance[j] = sum / float(samples);
      });
    }
    report.prepass_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    if (!options.save_path.empty()) {
      pc::save_point_cloud(options.save_path + suffix, cloud);
      report.file_bytes += std::filesystem::file_size(options.save_path + suffix);
    }
    pc::DiffusionOptions d;
    d.epsilon = m.params.epsilon;
    d.local_disk = m.params.local_disk;
    sc.point_clouds[i] = std::make_unique<pc::PointCloudDiffusion>(cloud.points, cloud.irradiance, *m.profile, d);
    const auto& st = sc.point_clouds[i]->stats();
    report.clouds += 1;
    report.points += st.point_count;
    report.memory_bytes += st.memory_bytes;
    report.build_seconds += st.build_seconds;
  }
  return report;
}

}  // namespace dermis
