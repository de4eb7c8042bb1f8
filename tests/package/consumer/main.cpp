// The consumer of the installed package (tests/package/install_consumer.sh): renders a unit
// sphere through a 4×4 window on 64×64 pixels and checks the answer — π·16² ≈ 804 covered
// pixels, the centre normal (0, 0, -1) at device depth -16 (16 pixels per unit) — then writes
// the picture. Exit 0 only when all holds.
#include <quadrix/quadrix.h>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2) return 2;
    try {
        quadrix::Scene scene = quadrix::Scene::FromText("solid sphere ball =r 1 =c 1 .6 .2;");
        quadrix::Renderer renderer;
        quadrix::Renderer::Options options;
        options.width = options.height = 64;
        options.camera = quadrix::View::Parallel({0, 0, -1});
        options.camera->halfWidth = options.camera->halfHeight = 2;
        const quadrix::Rendering r = renderer.Render(scene, options);
        const std::size_t c = r.Index(32, 32);  // the pixel whose centre is (1/32, -1/32)
        const double expected = -16 * std::sqrt(1 - 2.0 / 1024);
        const bool ok = std::abs(static_cast<double>(r.CoveredCount()) - M_PI * 256) < 20 &&
                        // The Frame keeps depth as a float and packs the normal (within 7e-5).
                        std::abs(r.normal[3 * c + 2] + std::sqrt(1 - 2.0 / 1024)) < 7e-5 &&
                        std::abs(r.depth[c] - expected) < 1e-6 && r.solidNames.size() == 1 &&
                        r.image.At(32, 32)[0] > r.image.At(32, 32)[2];
        r.image.Write(argv[1]);
        std::printf("quadrix %s: %zu pixels covered, centre depth %.9f (expected %.9f): %s\n",
                    quadrix::VersionString(), r.CoveredCount(), r.depth[c], expected,
                    ok ? "ok" : "WRONG");
        return ok ? 0 : 1;
    } catch (const quadrix::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
