// Renders a scene file of any supported format with the installed C++ API (docs/api.md):
//
//   render_file SCENE OUT.png [WIDTHxHEIGHT] [ENGINE]
//
// Prints how many pixels the solids cover; on an error prints every diagnostic
// (file:line:column) and exits 1, writing nothing.
#include <quadrix/quadrix.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
    if (argc < 3) {
        std::fprintf(stderr, "usage: render_file SCENE OUT.png [WIDTHxHEIGHT] [ENGINE]\n");
        return 2;
    }
    quadrix::Renderer::Options options;
    options.width = 320;
    options.height = 240;
    if (argc > 3 && std::sscanf(argv[3], "%dx%d", &options.width, &options.height) != 2) {
        std::fprintf(stderr, "render_file: expected WIDTHxHEIGHT, found '%s'\n", argv[3]);
        return 2;
    }
    if (argc > 4) options.engine = argv[4];
    try {
        const quadrix::Scene scene = quadrix::Scene::FromFile(argv[1]);
        for (const quadrix::Message& w : scene.Warnings())
            std::fprintf(stderr, "%s\n", w.Format().c_str());
        quadrix::Renderer renderer;
        const quadrix::Rendering result = renderer.Render(scene, options);
        for (const std::string& note : result.notes)
            std::fprintf(stderr, "note: %s\n", note.c_str());
        result.image.Write(argv[2]);
        std::printf("%s: %zu of %d pixels covered by %zu solids (engine %s, %.3f s)\n", argv[2],
                    result.CoveredCount(), result.width * result.height, result.solidNames.size(),
                    result.engine.c_str(), result.seconds);
        return 0;
    } catch (const quadrix::Error& e) {
        for (const quadrix::Message& m : e.Messages())
            std::fprintf(stderr, "%s\n", m.Format(true).c_str());
        return 1;
    }
}
