// Stand-ins for the CGAL-based steps when wirerig is built without CGAL (WIRERIG_WITH_CGAL=OFF,
// CGAL being GPL): the automatic curve skeleton and the alpha wrap are refused with the reason;
// rig descriptions and assets' own skeletons work as usual.
#include "wirerig/rig/curve_skeleton.h"
#include "wirerig/rig/watertight_proxy.h"

namespace wirerig {
namespace {

constexpr const char* kWithoutCgal =
    "this wirerig was built without CGAL (WIRERIG_WITH_CGAL=OFF): no automatic curve skeleton; "
    "give a rig description (--description) or use an asset with a skeleton";

}  // namespace

Result<CurveSkeleton> ExtractCurveSkeleton(const Mesh&) {
  return Error{std::string("curve skeleton: ") + kWithoutCgal};
}

Result<WatertightProxy> WrapWatertight(const Mesh&, const WrapOptions&) {
  return Error{std::string("alpha wrap: ") + kWithoutCgal};
}

}  // namespace wirerig
