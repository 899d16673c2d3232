// Everything the integrator reads, built once from a parsed SceneDesc: shapes in
// Embree, materials, textures, media, lights with their selection distribution,
// and the camera.
#pragma once

#include <memory>
#include <vector>

#include "dermis/core/distribution.h"
#include "dermis/geometry/embree_scene.h"
#include "dermis/geometry/shape.h"
#include "dermis/lights/light.h"
#include "dermis/lights/light_selection.h"
#include "dermis/materials/material.h"
#include "dermis/materials/medium.h"
#include "dermis/materials/texture.h"
#include "dermis/render/camera.h"
#include "dermis/render/point_cloud_prepass.h"
#include "dermis/sss/pointcloud/point_cloud_diffusion.h"
#include "dermis/render/subsurface_method.h"
#include "dermis/scene/scene_desc.h"

namespace dermis {

struct RenderScene {
  std::vector<Shape> shapes;
  std::unique_ptr<EmbreeScene> embree;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<HomogeneousMedium> media;
  std::vector<std::unique_ptr<SubsurfaceMethod>> subsurface;  // per Subsurface material
  // Per shape: the point cloud of a `pointcloud` subsurface object (else null).
  std::vector<std::unique_ptr<sss::pointcloud::PointCloudDiffusion>> point_clouds;
  PointCloudReport point_cloud_report;
  std::vector<Light> lights;
  LightSelection light_selection;     // which light next-event estimation samples
  std::vector<int> infinite_lights;
  bool has_interfaces = false;        // any shape with an `interface` material
  // Per medium: can a shadow ray from inside it reach a light? Not when the medium only
  // fills shapes with opaque or refractive boundaries and holds no light (e.g. skin
  // under a dielectric): next-event estimation there would only find the boundary.
  std::vector<char> medium_sees_lights;
  int camera_medium = -1;
  PerspectiveCamera camera;
  FilmDesc film;
  RenderSettingsDesc settings;
};

// Throws SceneError for problems found while building (e.g. an unreadable texture),
// and adds warnings to `diagnostics`.
// Also runs the point-cloud pre-pass when a material asks for it.
std::unique_ptr<RenderScene> build_render_scene(const SceneDesc& desc, Diagnostics& diagnostics,
                                                const PointCloudOptions& point_clouds = {});

// A triangulated unit sphere: (2n x n) quads in latitude/longitude, outward winding.
void tessellate_sphere(float radius, int n, std::vector<Vec3>& positions, std::vector<uint32_t>& indices);

}  // namespace dermis
