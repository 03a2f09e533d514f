#pragma once
// The demo scene: analytic shapes combined with CSG (interim: closed forms here until the shape
// module lands on main).

#include <algorithm>
#include <string>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom::cli {

/// Sphere of radius 1 minus a box corner, united with a torus around it.
struct DemoScene {
  using scalar_type = float;
  static constexpr SdfKind kind = SdfKind::bound;
  float operator()(const Vec3<float>& p) const noexcept {
    const float sphere = norm(p) - 1.0f;
    const Vec3<float> q = abs(p - Vec3<float>{0.6f, 0.6f, 0.6f}) - Vec3<float>::constant(0.5f);
    const float box = norm(max(q, Vec3<float>::zero())) + std::min(max_component(q), 0.0f);
    const float body = std::max(sphere, -box);
    const float qx = std::sqrt(p.x * p.x + p.y * p.y) - 1.5f;
    const float torus = std::sqrt(qx * qx + p.z * p.z) - 0.2f;
    return std::min(body, torus);
  }
  Aabb<float> bounds() const noexcept { return Aabb<float>({-1.7f, -1.7f, -1}, {1.7f, 1.7f, 1}); }
};

inline DemoScene make_demo_scene() { return {}; }
inline std::string demo_scene_description() {
  return "sphere minus box, united with a torus (analytic, CSG)";
}

} // namespace ebgeom::cli
