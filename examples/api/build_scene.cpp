// Builds a scene in code with the installed C++ API (docs/api.md): a drilled block from
// half-space solids and CSG, a sphere written in the scene language, lights and a view; renders
// it with two engines, composes a second scene into the picture by depth and writes PNG files.
//
//   build_scene OUT_DIR
#include <quadrix/quadrix.h>

#include <cmath>
#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : ".";
    try {
        quadrix::Scene part;
        part.AddBox("block", {-2, -1, -1}, {2, 1, 1}, quadrix::Color{0.7, 0.75, 0.8})
            .AddCylinder("hole", {0, -2, 0}, {0, 2, 0}, 0.6)
            .AddCsg("drilled", quadrix::CsgOperation::kDifference, "block", "hole")
            // Anything of the scene language can be added as text: here a solid by its
            // dimensions, positioned with the language's transforms.
            .Append("solid sphere knob =r .5 =at 2 1 0 =c 1 .5 0;")
            .AddAmbientLight("fill", 0.15)
            .AddParallelLight("key", 0.85, {-1, 2, -3});
        quadrix::View iso = quadrix::View::Parallel({1, 1.2, -1.5});
        iso.id = "iso";
        part.AddView(iso);

        quadrix::Renderer renderer;
        quadrix::Renderer::Options options;
        options.width = 320;
        options.height = 240;
        // A fixed window, so that both scenes below are seen through the same view.
        quadrix::View camera = iso;
        camera.halfWidth = 4;
        options.camera = camera;
        const quadrix::Rendering exact = renderer.Render(part, options);
        options.engine = "scanline";  // the UniQuadrix scan-line engine, composed with raycast
        const quadrix::Rendering scan = renderer.Render(part, options);
        std::size_t differ = 0;
        for (std::size_t k = 0; k < exact.surface.size(); ++k)
            differ += exact.surface[k] != scan.surface[k];
        std::printf("raycast and scanline differ on %zu of %zu pixels\n", differ,
                    exact.surface.size());

        quadrix::Scene floor;
        floor.AddBox("slab", {-4, -1.5, -3}, {4, -1, 3}, quadrix::Color{0.3, 0.5, 0.3});
        options.engine = "raycast";
        const quadrix::Rendering withFloor =
            quadrix::Compose(exact, renderer.Render(floor, options));

        exact.image.Write(dir + "/build_scene.png");
        withFloor.image.Write(dir + "/build_scene_floor.png");
        const std::size_t c = exact.Index(exact.width / 2, exact.height / 2);
        if (exact.surface[c] == quadrix::Rendering::kNone)
            std::printf("centre pixel: background\n");
        else
            std::printf("centre pixel: surface %s of solid %s, depth %.6f\n",
                        exact.surfaceNames[exact.surface[c]].c_str(),
                        exact.solidNames[exact.solid[c]].c_str(), exact.depth[c]);
        std::printf("covered: %zu alone, %zu with the floor\n", exact.CoveredCount(),
                    withFloor.CoveredCount());
        return 0;
    } catch (const quadrix::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
}
