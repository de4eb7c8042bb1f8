#include "quadrix/viewer/section.h"

namespace quadrix::viewer {

void SectionPlane::Toggle(const Camera& camera, const Vec3& centre) {
    if (on) {
        on = false;
        return;
    }
    on = true;
    normal = Normalize(camera.toward);
    offset = Dot(normal, centre);
}

std::optional<Plane> SectionPlane::ToPlane() const {
    if (!on) return std::nullopt;
    return Plane{normal.x, normal.y, normal.z, -offset};
}

}  // namespace quadrix::viewer
