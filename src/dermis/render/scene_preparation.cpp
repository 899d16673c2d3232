#include "dermis/render/scene_preparation.h"

#include <fmt/format.h>

#include <chrono>
#include <stdexcept>

#include "dermis/render/object_chords.h"
#include "dermis/render/scene_assembly.h"
#include "dermis/render/subsurface/coefficients.h"

namespace dermis {

PreparationReport prepare_scene(RenderScene& sc, const PreparationOptions& options) {
  using Clock = std::chrono::steady_clock;
  PreparationReport report;
  const auto t0 = Clock::now();
  const std::size_t stages = sc.subsurface_params.size() + sc.volumetric_media.size();
  ProcessGroup& group = options.group ? *options.group : single_process();
  {
    Progress progress("Subsurface methods", int64_t(stages), stages > 0 ? options.progress : Progress::Style::kQuiet);
    auto check_cancel = [&] {
      if (group.any(options.cancel && options.cancel->load())) throw Interrupted();
    };
    // The albedo-inversion tables first, made once for the group; the methods then
    // look them up (the other tables, profiles and probes, are quick: each process
    // makes its own).
    {
      std::vector<SubsurfaceParams> table_params = sc.subsurface_params;
      for (const RenderScene::VolumetricMedium& v : sc.volumetric_media) {
        table_params.push_back(v.params);
        table_params.back().boundary = SubsurfaceParams::Boundary::Dielectric;
      }
      check_cancel();
      prepare_albedo_inversions(table_params, group);
    }
    sc.subsurface.clear();
    const std::vector<double> chords = subsurface_object_chords(sc);
    for (std::size_t k = 0; k < sc.subsurface_params.size(); ++k) {
      const SubsurfaceParams& p = sc.subsurface_params[k];
      check_cancel();
      try {
        sc.subsurface.push_back(
            std::make_unique<SubsurfaceMaterial>(make_subsurface_material(p, &sc.textures, chords[k])));
      } catch (const std::invalid_argument& e) {
        throw SceneError(p.loc, fmt::format("subsurface: {}", e.what()));
      }
      progress.advance();
    }
    // The volumetric reference has a dielectric boundary: its (reflectance, mfp)
    // inversion uses the dielectric table.
    // Textured parameters: the medium of the textures' mean here; each path takes the one
    // of its entry point (volumetric_texture.h), through the same table.
    sc.textured_volumetric_of_medium.clear();
    for (std::size_t i = 0; i < sc.volumetric_media.size(); ++i) {
      RenderScene::VolumetricMedium& v = sc.volumetric_media[i];
      check_cancel();
      SubsurfaceParams as_dielectric = v.params;
      as_dielectric.boundary = SubsurfaceParams::Boundary::Dielectric;
      v.inversions = AlbedoInversions(as_dielectric);
      v.roughness = BoundaryRoughness(as_dielectric, false, &sc.textures);
      const Coefficients k = coefficients_from(medium_at(as_dielectric), v.inversions, v.roughness.constant().x);
      sc.media[v.medium] = HomogeneousMedium::from_coefficients(k.sigma_a, k.sigma_s, 1, v.params.g);
      const bool inversion_per_entry = v.roughness.textured() && !v.inversions.empty() && !v.inversions.single();
      if (v.params.textured() || inversion_per_entry) {
        sc.textured_volumetric_of_medium.resize(sc.media.size(), -1);
        sc.textured_volumetric_of_medium[v.medium] = int(i);
      }
      progress.advance();
    }
    progress.finish();
  }
  report.subsurface_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  report.point_clouds = build_point_clouds(sc, options.point_clouds, options.progress, options.cancel, &group);
  sc.prepared = true;
  return report;
}

std::unique_ptr<RenderScene> build_render_scene(const SceneDesc& desc, Diagnostics& diagnostics,
                                                const PointCloudOptions& point_clouds) {
  auto sc = assemble_scene(desc, diagnostics);
  PreparationOptions options;
  options.point_clouds = point_clouds;
  prepare_scene(*sc, options);
  return sc;
}

}  // namespace dermis
