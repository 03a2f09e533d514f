// A downstream project: includes the umbrella header and evaluates something.
#include <ebgeom/ebgeom.hpp>

int main() {
  const ebgeom::Aabb<double> box = ebgeom::Aabb<double>::of({0, 0, 0}, {1, 1, 1});
  return box.distance({2, 0.5, 0.5}) == 1.0 ? 0 : 1;
}
