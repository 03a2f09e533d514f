// Compiles the AMReX and Chombo adapters against minimal stand-ins of the APIs they use (in
// mock/), once with SPACEDIM 3 and once with 2, and checks sign and slicing through them.
#include <gtest/gtest.h>

#include <memory>

#include "ebgeom_amrex.hpp"
#include "ebgeom_chombo.hpp"

namespace {

struct Ball {
  using scalar_type = double;
  static constexpr ebgeom::SdfKind kind = ebgeom::SdfKind::exact;
  double operator()(const ebgeom::Vec3<double>& p) const noexcept { return ebgeom::norm(p) - 1.0; }
  ebgeom::Aabb<double> bounds() const noexcept {
    return ebgeom::Aabb<double>::of({-1, -1, -1}, {1, 1, 1});
  }
};

constexpr int dim = AMREX_SPACEDIM;

} // namespace

TEST(AdapterMock, AmrexImplicitFunction) {
  ebgeom::EbOptions opt;
  opt.z_slice = 0.5;
  const ebgeom::AmrexImplicitFunction<Ball> f(Ball{}, opt);
  const ebgeom::AmrexImplicitFunction<Ball> copy = f; // AMReX stores it by value
  const double z = dim == 3 ? 0.0 : 0.5;              // 2D evaluates the slice
  amrex::RealArray p{};
  p[0] = 2.0;
  p[1] = 0.0;
  const double expected = -(std::sqrt(4.0 + z * z) - 1.0); // fluid outside: negative there
  EXPECT_DOUBLE_EQ(copy(p), expected);
#if AMREX_SPACEDIM == 3
  EXPECT_DOUBLE_EQ(f(2.0, 0.0, 0.0), expected);
#else
  EXPECT_DOUBLE_EQ(f(2.0, 0.0), expected);
#endif
  EXPECT_EQ(&copy.function().sdf(), &f.function().sdf());
}

TEST(AdapterMock, ChomboImplicitFunction) {
  ebgeom::EbOptions opt;
  opt.fluid = ebgeom::FluidSide::inside;
  opt.z_slice = 0.5;
  const ChomboImplicitFunction<Ball> f(Ball{}, opt);
  std::unique_ptr<BaseIF> clone(f.newImplicitFunction());
  RealVect p{};
  p.v[0] = 0.25;
  const double z = dim == 3 ? 0.0 : 0.5;
  const double expected = std::sqrt(0.0625 + z * z) - 1.0; // fluid inside: +S, negative inside
  EXPECT_DOUBLE_EQ(clone->value(p), expected);
  EXPECT_DOUBLE_EQ(f.value(p), expected);
  EXPECT_EQ(&dynamic_cast<ChomboImplicitFunction<Ball>&>(*clone).function().sdf(),
            &f.function().sdf());
}
