// The per-frame tables of engine `raycast` (step 1 of a render, raycast.cpp; DESIGN.md "Engines
// in more detail"): per half-space its coefficients regrouped for rays along z (RayHalfSpace,
// ray_literal.h), per literal of every body a global "tag" naming (half-space, body,
// complemented, opaque). Tags are the ids carried by interval endpoints, so the visible endpoint
// of a pixel names its surface and body; a Hit is such an endpoint (depth, tag, solid).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "quadrix/engines/raycast/eval_names.h"
#include "quadrix/flatten/flat_scene.h"
#include "quadrix/frame/packed_normal.h"

namespace quadrix::raycast {

// Per-literal facts looked up from an endpoint's tag.
struct Tag {
    std::int32_t halfSpace = -1;
    std::int32_t body = -1;
    bool complemented = false;
    bool opaque = true;
};

// A pixel's visible point: its depth, the tag of the endpoint and the solid it belongs to.
struct Hit {
    double t = HUGE_VAL;
    std::int32_t tag = -1;
    std::int32_t solid = -1;
};

struct SceneTables {
    std::vector<RayHalfSpace> halfSpaces;
    std::vector<Tag> tags;
    std::vector<std::int32_t> bodyFirstTag;  // body b's literals are tags [first[b], first[b+1])
    std::vector<char>
        bodyValid;  // 0 when a literal names a missing half-space (char: read per body)
    // Per half-space: true for a plane, whose world normal (FlatScene::WorldNormal) is the same
    // at every point and is computed once here, in `planeNormal`, and packed as the Frame holds
    // it in `packedPlaneNormal` (frame/packed_normal.h), so pixels do not pack it again.
    std::vector<char> constantNormal;  // char, not bool: read for every covered pixel
    std::vector<Vec3> planeNormal;
    std::vector<PackedNormal> packedPlaneNormal;
    // 0, 1, 2, … (one per tag): body b's literal tags as an array, tagSequence.data() +
    // bodyFirstTag[b] (TileReduction::ReduceBody takes its literals as an array).
    std::vector<std::int32_t> tagSequence;

    explicit SceneTables(const FlatScene& scene);

    // Re-centring points for the quadrics (ray_literal.h): the quadric's own centre when it has
    // one (RayHalfSpace::Centre), else the image centre at depth 0 (ReferenceAnchor). They depend
    // on nothing but the half-space, so bounds (culling) cannot change a single bit of the result.
    static Vec3 ReferenceAnchor(const FlatScene& scene);
    static Vec3 ReferencePoint(const FlatHalfSpace& hs, const Vec3& anchor);

    const Tag& TagOf(std::int32_t tag) const { return tags[static_cast<std::size_t>(tag)]; }

    // All of body b's literal tags, in its order.
    const std::int32_t* BodyTags(std::size_t b) const {
        return tagSequence.data() + bodyFirstTag[b];
    }
    std::size_t BodyTagCount(std::size_t b) const {
        return static_cast<std::size_t>(bodyFirstTag[b + 1] - bodyFirstTag[b]);
    }
    // A body that is ∅ on every ray: a literal names a missing half-space, or it has none.
    bool BodyVoid(std::size_t b) const {
        return !bodyValid[b] || bodyFirstTag[b] == bodyFirstTag[b + 1];
    }

    // The visible end of one interval: its near end when it is finite and on an opaque surface,
    // else its far end on the same terms; false when neither is.
    bool VisibleEnd(double lo, std::int32_t loId, double hi, std::int32_t hiId, double& t,
                    std::int32_t& tag) const {
        if (loId >= 0 && std::isfinite(lo) && TagOf(loId).opaque) {
            t = lo;
            tag = loId;
            return true;
        }
        if (hiId >= 0 && std::isfinite(hi) && TagOf(hiId).opaque) {
            t = hi;
            tag = hiId;
            return true;
        }
        return false;
    }
};

}  // namespace quadrix::raycast
