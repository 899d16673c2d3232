// A small scene that exercises every path-tracer branch, for the renderer's tests.
#pragma once

#include "dermis/core/transform.h"
#include "dermis/scene/scene_desc.h"

namespace dermis::testing {

// Diffuse sphere in a coloured dielectric-bounded medium on a floor, lit by a
// uniform environment and a spot light: exercises every path-tracer branch.
inline SceneDesc small_scene() {
  SceneDesc d;
  d.camera.camera_to_world = Transform::look_at({0, 1, -5}, {0, 0, 0}, {0, 1, 0}).inverse();
  d.camera.fov = 40;
  d.film.xres = 40;
  d.film.yres = 30;
  d.settings.max_depth = 64;
  MaterialDesc glass;
  glass.type = MaterialDesc::Type::Dielectric;
  glass.eta = 1.4f;
  d.materials.push_back(glass);
  MaterialDesc floor;
  floor.reflectance.value = RGB(0.7f, 0.6f, 0.5f);
  d.materials.push_back(floor);
  MediumDesc m;
  m.sigma_s = RGB(2, 3, 4);
  m.sigma_a = RGB(0.1f, 0.3f, 0.6f);
  d.media.push_back(m);
  ShapeDesc ball;
  ball.type = ShapeDesc::Type::Sphere;
  ball.material = 0;
  ball.inside_medium = 0;
  ball.has_medium_interface = true;
  d.shapes.push_back(ball);
  ShapeDesc plane;
  plane.material = 1;
  plane.mesh.positions = {{-10, -1, -10}, {10, -1, -10}, {10, -1, 10}, {-10, -1, 10}};
  plane.mesh.indices = {0, 2, 1, 0, 3, 2};
  d.shapes.push_back(plane);
  LightDesc env;
  env.type = LightDesc::Type::Infinite;
  env.spectrum = RGB(0.3f);
  d.lights.push_back(env);
  LightDesc spot;
  spot.type = LightDesc::Type::Spot;
  spot.from = {2, 4, -2};
  spot.to = {0, 0, 0};
  spot.spectrum = RGB(20);
  d.lights.push_back(spot);
  return d;
}

}  // namespace dermis::testing
