#include "quadrix/scene/light_rig.h"

namespace quadrix::scene {

std::vector<Light> DefaultRig(const Vec3& towardViewer, const Vec3& right, const Vec3& up) {
    Light ambient;
    ambient.id = "rig_ambient";
    ambient.kind = Light::Kind::kAmbient;
    ambient.intensity = kRigAmbient;
    ambient.isRig = true;

    Light head;
    head.id = "rig_headlight";
    head.kind = Light::Kind::kParallel;
    head.intensity = kRigHeadlight;
    head.direction = Normalize(towardViewer);
    head.isRig = true;

    Light key = head;
    key.id = "rig_key";
    key.intensity = kRigKey;
    key.direction =
        Normalize(Normalize(towardViewer) * 0.5 + Normalize(up) - Normalize(right) * 0.6);
    return {ambient, head, key};
}

}  // namespace quadrix::scene
