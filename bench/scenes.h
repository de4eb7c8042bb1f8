// Benchmark scenes (issue 8), generated as UniQuadrix text so that every engine, the CLI and the
// POV-Ray export see exactly the same input. Deterministic: fixed seeds, no clock.
#pragma once

#include <string>
#include <vector>

namespace quadrix::bench {

struct BenchScene {
    std::string name;    // short id, used in file names and tables
    std::string text;    // UniQuadrix source
    int primitives = 0;  // half-spaces in the scene (planes + quadrics)
};

// N spheres (fixed random placement in a 20-unit cube, overlapping) unioned, minus a cylinder:
// (∪ sphereᵢ) − drill, or with `distributed` the same solid written ∪(sphereᵢ − drill) (issue 24:
// cost must not depend on how the tree is written; named "spheresN_distributed").
BenchScene SpheresMinusCylinder(int n, bool distributed = false);
// Two crossing capped cylinders combined by `op` ('|', '&' or '-').
BenchScene TwoCylinders(char op);
// A closed trefoil ("clover knot") of `segments` mitered pipes with spheres at the joints.
BenchScene MiteredKnot(int segments);
// A − B1∩C1 − B2∩C2 − … with `pairs` pairs: 2^pairs products when normalised to a sum of products.
BenchScene SumOfProductsExplosion(int pairs);
// A scene read from a file under the source tree (examples).
BenchScene FromFile(const std::string& name, const std::string& path);

}  // namespace quadrix::bench
