// The table of bad inputs (trunk acceptance): each gives a one-line error with its position where
// there is a file, a non-zero exit code, no output file, and no crash (exit codes ≥ 128 would be
// signals). The first line of standard error is the error; source and caret lines may follow.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "quadrix/scene/diagnostics.h"
#include "quadrix/util/sanitizers.h"
#include "test_util.h"

namespace quadrix::testing {
namespace {

// A file's text, or a function that makes it when the row runs. gtest builds every row in every
// test process (ctest runs each test alone), so the big generated scenes are made only by the
// test that writes them: built eagerly they cost every process 0.1 s, 0.45 s under ASan.
struct FileText {
    FileText() = default;
    FileText(std::string t) : text(std::move(t)) {}  // NOLINT: implicit, rows list plain texts
    FileText(const char* t) : text(t) {}             // NOLINT
    std::string Get() const { return make ? make() : text; }
    std::string text;
    std::function<std::string()> make = {};
};
FileText Lazy(std::function<std::string()> make) {
    FileText f;
    f.make = std::move(make);
    return f;
}
using Files = std::map<std::string, FileText>;

struct BadInput {
    const char* name;
    Files files;                  // written into a temp dir; "main.uq" is rendered
    std::string extraArgs;        // appended to the command line ({dir} = temp dir)
    std::string expectFirstLine;  // regex searched in the first line of stderr
    // Shell commands run in the temp dir before quadrix (mkfifo, ln, ulimit: the same shell).
    std::string setup = {};
    // Rows that must give a correct picture instead of an error (exit 0, out.ppm written, lit:
    // some pixel at least this bright); 0 = an error row.
    int expectLitPixel = 0;
    // The other front ends (FrontEndRows): the whole command line after `quadrix` (in the temp
    // dir; {dir} = its path) instead of `render main.uq EXTRA -o out.png`. Such a row must leave
    // the directory as its setup left it (no output, no temporary file), and expectFirstLine is
    // searched in every line of stderr.
    std::string command = {};
    // A command row that must SUCCEED (exit 0) instead: `check`, a shell command run in the temp
    // dir afterwards ({quadrix} = the binary), must exit 0 too, and no temporary file may be left.
    // For reproducers whose right answer is not an error (a planted link ignored, a mode kept,
    // a picture equal to the reference engine's).
    std::string check = {};
};

void PrintTo(const BadInput& b, std::ostream* os) { *os << b.name; }

std::string IncludeChain(int depth, Files& files) {
    // main.uq reads f1.uq, f1 reads f2, …, f<depth> holds a sphere.
    for (int i = 1; i <= depth; ++i) {
        std::string next = i < depth ? "read \"f" + std::to_string(i + 1) + ".uq\";\n"
                                     : "quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);\n";
        files["f" + std::to_string(i) + ".uq"] = next;
    }
    return "read \"f1.uq\";\n";
}

// A v5 combination tree nested `depth` levels: {u {u … {l s} {l s}} {l s}}.
std::string DeepV5Tree(int depth) {
    // "{u " + tree + " {l s}}" applied `depth` times, built in linear time (the rows are made at
    // every test process's start, and depth 50,000 built by concatenation took seconds).
    std::string tree;
    tree.reserve(static_cast<std::size_t>(depth) * 11 + 5);
    for (int i = 0; i < depth; ++i) tree += "{u ";
    tree += "{l s}";
    for (int i = 0; i < depth; ++i) tree += " {l s}}";
    return "title {t}\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n"
           "put {r} comb region yes tree " +
           tree + "\n";
}

// Issue 23 (hardening): the output writer, bounded inputs, memory, importer ranges, degenerate
// directions, misleading messages. Each reproduces a defect found on the old main.
std::vector<BadInput> HardeningRows() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    const std::string rtView = "viewsize 4;\neye_pt 0 0 10;\n";
    const std::string v5Sphere = "title {t}\nput {s} ell V {0 0 0} A {1 0 0} B {0 1 0} C {0 0 1}\n";
    return {
        // ---- The one output writer: never replace a non-regular file or an input.
        {"OutputIsFifo",
         {{"main.uq", sphere}},
         "-o {dir}/fifo.png",
         R"(cannot write.*FIFO)",
         "mkfifo fifo.png"},
        {"OutputIsDirectory",
         {{"main.uq", sphere}},
         "-o {dir}/d.png",
         R"(cannot write.*directory)",
         "mkdir d.png"},
        {"OutputIsDanglingLink",
         {{"main.uq", sphere}},
         "-o {dir}/link.png",
         R"(cannot write.*symbolic link)",
         "ln -s nowhere.png link.png"},
        // A character device made in the temp dir (root only; else a FIFO stands in).
        {"OutputIsDeviceNode",
         {{"main.uq", sphere}},
         "-o {dir}/node.png",
         R"(cannot write.*(character device|FIFO))",
         "mknod node.png c 1 3 2>/dev/null || mkfifo node.png"},
        {"OutputIsTheScene",
         {{"main.uq", sphere}},
         "-o {dir}/main.uq.png",
         R"(cannot write.*input)",
         "ln main.uq main.uq.png"},
        {"OutputIsAFileTheSceneReads",
         {{"main.uq", "read \"part.uq\";\n"}, {"part.uq", sphere}},
         "-o {dir}/part.png",
         R"(cannot write.*input)",
         "ln part.uq part.png"},
        // The issue's `--dump-frame scene.uq` is now refused by its extension (not .qxf); the same
        // file under a .qxf name (a hard link) is refused as the input.
        {"DumpFrameIsTheScene",
         {{"main.uq", sphere}},
         "--dump-frame {dir}/main.uq",
         R"(error.*main\.uq)"},
        {"DumpFrameIsALinkToTheScene",
         {{"main.uq", sphere}},
         "--dump-frame {dir}/main.qxf",
         R"(cannot write.*main\.qxf.*input)",
         "ln main.uq main.qxf"},
        {"DumpFrameIsADirectory",
         {{"main.uq", sphere}},
         "--dump-frame {dir}/d.qxf",
         R"(cannot write.*d\.qxf.*directory)",
         "mkdir d.qxf"},
        {"DumpFrameIsTheOutput",
         {{"main.uq", sphere}},
         "-o {dir}/a.qxf --dump-frame ./a.qxf",
         R"(cannot write.*same file)"},
        // A directory nobody may create files in, root included (output_safety_test.cpp has the
        // chmod 555 case, run as nobody).
        {"OutputInReadOnlyDirectory",
         {{"main.uq", sphere}},
         "-o /proc/self/quadrix-x.png",
         R"(cannot write.*quadrix-x\.png)"},
        // ---- Bounded inputs: one reader, 256 MiB, for every path.
        {"SceneIsDevZero", {}, "/dev/zero", R"(/dev/zero.*larger than 256 MiB)"},
        {"StdinIsDevZero", {}, "- < /dev/zero", R"(standard input.*larger than 256 MiB)"},
        {"StdinIsClosed", {}, "- <&-", R"(cannot read standard input)"},
        {"RtViewIsDevZero",
         {{"main.uq", sphere}},
         "--rt-view /dev/zero",
         R"(rt-view.*larger than 256 MiB)"},
        {"ReadDevZero",
         {{"main.uq", "read \"/dev/zero\";\n"}},
         "",
         R"(main\.uq:1:\d+: error.*larger than 256 MiB)"},
        {"HugeAscFile",
         {},
         "{dir}/big.asc",
         R"(big\.asc.*larger than 256 MiB)",
         "truncate -s 300M big.asc"},
        {"HugeScadFile",
         {},
         "{dir}/big.scad",
         R"(big\.scad.*larger than 256 MiB)",
         "truncate -s 257M big.scad"},
        {"SceneIsADirectory", {}, "{dir}/sub.uq", R"(sub\.uq.*directory)", "mkdir sub.uq"},
        {"RtViewIsADirectory", {{"main.uq", sphere}}, "--rt-view {dir}", R"(rt-view.*directory)"},
        // ---- Memory and time: a size the budget cannot hold is a clear error, not SIGABRT.
        {"ImageLargerThanMaxMemory",
         {{"main.uq", sphere}},
         "--size 4096x4096 --max-memory 100M",
         R"(4096x4096.*memory budget is 100 MiB \(--max-memory\))"},
        {"MaxMemoryMalformed",
         {{"main.uq", sphere}},
         "--max-memory lots",
         R"(error: --max-memory.*lots)"},
        {"TimeLimitOnStalledInput",
         {},
         "- --time-limit 0.3",
         R"(error: time limit of 0\.3 s)",
         "sleep 2 |"},
        {"TimeLimitMalformed", {{"main.uq", sphere}}, "--time-limit -1", R"(error: --time-limit)"},
        // ---- Animation options on a still picture: usage errors, not silently ignored (issue 22).
        {"FrameRangeWithoutFrames",
         {{"main.uq", sphere}},
         "--frame-range 2:5",
         R"(error: --frame-range: there is no animation.*--frames, --turntable or --views)"},
        {"ResumeOnAStillPicture",
         {{"main.uq", sphere}},
         "--resume",
         R"(error: --resume: a still picture has no frames)"},
        // ---- BRL-CAD: numbers beyond int are positioned errors (were UBSan float-cast overflow).
        {"V4ColorTableHugeId",
         {{"m.asc", "I 1 v4\nt\nm 4 2.5e12 3 0 0 0\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*low region id)"},
        {"V4ColorTableBadRgb",
         {{"m.asc", "I 1 v4\nt\nm 4 1 3 0 1e12 0\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*green)"},
        {"V5ColorHuge",
         {{"m.asc", v5Sphere + "color 1 2 1e12 0 0\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*red)"},
        {"V5RegionIdHuge",
         {{"m.asc", v5Sphere + "put {r} comb region yes tree {l s}\n"
                               "attr set {r} {region} {R} {region_id} {1e12}\n"}},
         "{dir}/m.asc",
         R"(m\.asc:4:\d+: error.*region_id)"},
        {"V5ArbnHugeCount",
         {{"m.asc", "title {t}\nput {a} arbn N 1e12 P0 {1 0 0 1}\n"}},
         "{dir}/m.asc",
         R"(m\.asc:2:\d+: error.*N)"},
        {"V5TreeTooDeep",
         {{"m.asc", Lazy([] { return DeepV5Tree(2001); })}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*deeper than 2000)"},
        // ---- OpenSCAD: non-positive sizes are errors (OpenSCAD draws nothing).
        {"ScadNegativeSphere",
         {{"m.scad", "sphere(r=-1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadNegativeCube",
         {{"m.scad", "cube([-1,-1,-1]);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadZeroCylinder",
         {{"m.scad", "cylinder(h=0, r=1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadNegativeRadius",
         {{"m.scad", "cylinder(h=2, r1=-1, r2=1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*negative)"},
        // ---- rt views: the zero quaternion is no rotation.
        {"RtViewZeroQuaternion",
         {{"main.uq", sphere}, {"v.rt", rtView + "orientation 0 0 0 0;\n"}},
         "--rt-view {dir}/v.rt",
         R"(v\.rt:3:1: error.*zero quaternion)"},
        // ---- Messages: control bytes are shown, not printed raw.
        {"NulByteInReadPath",
         {{"main.uq", std::string("read \"a\0b\";\n", 12)}},
         "",
         R"(main\.uq:1:1: error: cannot read .*a\\x00b)"},
        {"NulByteInV5Name",
         {{"m.asc", std::string("title {t}\nput {a\0b} ell V {0 0 0} A {1 0 0} B {0 1 0}\n", 54)}},
         "{dir}/m.asc",
         R"(m\.asc:2:1: error: primitive 'a\\x00b')"},
        {"NulByteInScad",
         {{"m.scad", std::string("sph\0ere(r=1);\n", 14)}},
         "{dir}/m.scad",
         // Our reader's error, or (it does not parse, so OpenSCAD evaluates it) OpenSCAD's.
         R"(m\.scad:1(:4: error: .*'\\x00'|: error: OpenSCAD: Parser error))"},
        // ---- More of the same families.
        {"OutputIsASocket",
         {{"main.uq", sphere}},
         "-o {dir}/sock.png",
         R"(cannot write.*socket)",
         "python3 -c 'import socket; socket.socket(socket.AF_UNIX).bind(\"sock.png\")'"},
        {"OutputLinksToADirectory",
         {{"main.uq", sphere}},
         "-o {dir}/l.png",
         R"(cannot write.*directory)",
         "mkdir d && ln -s d l.png"},
        {"OutputLinksToAFifo",
         {{"main.uq", sphere}},
         "-o {dir}/l.png",
         R"(cannot write.*FIFO)",
         "mkfifo f && ln -s f l.png"},
        {"OutputLinksToTheScene",
         {{"main.uq", sphere}},
         "-o {dir}/l.png",
         R"(cannot write.*input)",
         "ln -s main.uq l.png"},
        {"DumpFrameIsADanglingLink",
         {{"main.uq", sphere}},
         "--dump-frame {dir}/l.qxf",
         R"(cannot write.*symbolic link)",
         "ln -s nowhere l.qxf"},
        // A link to a device: only lstat/stat/realpath touch /dev/null, it is never opened.
        {"OutputLinksToDevNull",
         {{"main.uq", sphere}},
         "-o {dir}/null.png",
         R"(cannot write.*null\.png.*character device)",
         "ln -s /dev/null null.png"},
        {"ReadADirectory",
         {{"main.uq", "read \"sub\";\n"}},
         "",
         R"(main\.uq:1:\d+: error.*directory)",
         "mkdir sub"},
        {"RtViewMissing",
         {{"main.uq", sphere}},
         "--rt-view {dir}/none.rt",
         R"(rt-view.*none\.rt.*No such file)"},
        {"RtViewNanQuaternion",
         {{"main.uq", sphere}, {"v.rt", rtView + "orientation nan 0 0 1;\n"}},
         "--rt-view {dir}/v.rt",
         R"(v\.rt:3:\d+: error.*finite)"},
        {"ScadNegativeDiameter",
         {{"m.scad", "sphere(d=-2);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadZeroCube",
         {{"m.scad", "cube(0);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadFlatCube",
         {{"m.scad", "cube([1, 0, 1]);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*size\[1\].*positive)"},
        {"ScadNegativeHeight",
         {{"m.scad", "cylinder(h=-1, r=1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*h = -1.*positive)"},
        {"ScadBothRadiiZero",
         {{"m.scad", "cylinder(h=1, r1=0, r2=0);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*both zero)"},
        {"ScadNestedNegativeSphere",
         {{"m.scad", "translate([1, 0, 0]) {\n  union() {\n    sphere(r=-3);\n  }\n}\n"}},
         "{dir}/m.scad",
         R"(m\.scad:3:5: error.*positive)"},
        {"ScadHugeScale",
         {{"m.scad", "scale([1e308, 1, 1]) sphere(1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:\d+: error.*cannot be inverted)"},
        {"V4ColorTableNegativeId",
         {{"m.asc", "I 1 v4\nt\nm 4 -5 3 0 0 0\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:5: error.*low region id)"},
        {"V5ColorFraction",
         {{"m.asc", v5Sphere + "color 1 2 0.5 0 0\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*red: '0\.5')"},
        {"V5AircodeHuge",
         {{"m.asc", v5Sphere + "put {r} comb region yes tree {l s}\n"
                               "attr set {r} {region} {R} {aircode} {-1e300}\n"}},
         "{dir}/m.asc",
         R"(m\.asc:4:\d+: error.*aircode)"},
        {"V5ArbnNegativeCount",
         {{"m.asc", "title {t}\nput {a} arbn N -2 P0 {1 0 0 1}\n"}},
         "{dir}/m.asc",
         R"(m\.asc:2:\d+: error.*N)"},
        {"V5TreeVeryDeep",
         {{"m.asc", Lazy([] { return DeepV5Tree(50000); })}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*deeper than 2000)"},
        // ---- Correct pictures where wrong ones (or misleading errors) came before.
        {"SceneIsAFifo",
         {},
         "{dir}/p.uq",
         "",
         "mkfifo p.uq; (printf 'quadric s <1 1 1 0 0 0 0 0 0 -1>; body ball (s);' > p.uq &)",
         100},
        {"SubnormalLightDirection",
         {{"main.uq", sphere + "light l1 1 0 0 -5e-324;\n"}},
         "",
         "",
         "",
         200},
        {"HugeDiagonalLight",
         {{"main.uq", sphere + "light l1 1 -1e300 -1e300 -1e300;\n"}},
         "",
         "",
         "",
         200},
        {"HugeDiagonalVpn",
         {{"main.uq", sphere + "view v vpn 1e300 1e300 1e300;\n"}},
         "",
         "",
         "",
         100},
        {"TinyQuaternion",
         {{"main.uq", sphere}, {"v.rt", rtView + "orientation 0 0 1e-300 1e-300;\n"}},
         "--rt-view {dir}/v.rt",
         "",
         "",
         100},
        {"ScadConeWithZeroTop",
         {{"m.scad", "cylinder(h=2, r1=1, r2=0);\n"}},
         "{dir}/m.scad",
         "",
         "",
         100},

        {"HugeLightDirection", {{"main.uq", sphere + "light l1 1 0 0 -1e200;\n"}}, "", "", "", 200},
        {"TinyLightDirection",
         {{"main.uq", sphere + "light l1 1 0 0 -1e-200;\n"}},
         "",
         "",
         "",
         200},
        {"TinyVpn", {{"main.uq", sphere + "view v vpn 0 0 1e-200;\n"}}, "", "", "", 100},
        {"HugeVpnAndVup",
         {{"main.uq", sphere + "view v vpn 0 0 1e200 vup 0 1e300 0;\n"}},
         "",
         "",
         "",
         100},
        {"ScadWithByteOrderMark",
         {{"m.scad", "\xEF\xBB\xBFsphere(r=1);\n"}},
         "{dir}/m.scad",
         "",
         "",
         100},
        {"RtViewUnnormalisedQuaternion",
         {{"main.uq", sphere}, {"v.rt", rtView + "orientation 0 0 0 2;\n"}},
         "--rt-view {dir}/v.rt",
         "",
         "",
         100},
        {"V5TreeAtTheDepthLimit",
         {{"m.asc", Lazy([] { return DeepV5Tree(2000); })}},
         "{dir}/m.asc",
         "",
         "",
         100},
    };
}

// Rows that need `ulimit -v`: AddressSanitizer reserves terabytes of address space and cannot
// even start under it, so the sanitizer build leaves them out.
std::vector<BadInput> AddressLimitRows() {
#if QUADRIX_ASAN
    return {};
#else
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    return {
        {"ImageLargerThanUlimit",
         {{"main.uq", sphere}},
         "--size 8192x8192",
         R"(8192x8192.*memory budget.*ulimit -v)",
         "ulimit -v 2097152"},
        // 200 MB of blanks (under the input limit) in 300 MB of address space: the reader's
        // copies fail to allocate, and std::bad_alloc is caught in main.
        {"AllocationFailureIsAnError",
         {},
         "{dir}/big.uq",
         R"(error: out of memory)",
         "head -c 200000000 /dev/zero | tr '\\0' ' ' > big.uq; ulimit -v 300000"},
    };
#endif
}

// Issue 23 items 3, 4 and 6 (second part): complexity guards (each scene once took minutes on
// some engine, docs/performance.md "Complexity guards"), coefficients of any magnitude (a quadric
// scaled by 1e308 drew nothing), the read fan-out budget, and more importer reproducers.
std::string CoincidentBallUnion(int n) {
    std::string s = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\n", u;
    for (int i = 0; i < n; ++i) {
        s += "body b" + std::to_string(i) + " (s);\n";
        u += (i ? " | b" : "b") + std::to_string(i);
    }
    return s + "csg u (" + u + ");\n";
}

// A unit ball cut by n - 1 planes at distance 0.9 with directions spread by a fixed recurrence
// (a spherical Fibonacci lattice): one body of n literals.
std::string BodyOfLiterals(int n) {
    std::string s = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\n", lits = "s";
    for (int i = 1; i < n; ++i) {
        const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
        const double phi = 2.399963229728653 * i;
        s += fmt::format("plane p{} <{:.6f} {:.6f} {:.6f} -0.9>;\n", i, r * std::cos(phi),
                         r * std::sin(phi), z);
        lits += " p" + std::to_string(i);
    }
    return s + "body big (" + lits + ");\n";
}

// A 2 × 2 × 2 block seen end-on with n thin holes drilled along the view, all literals of one body:
// complemented cylinders parallel to the rays, which no rectangle's reduction can drop (each holds
// on all of a ray or none of it, tile_reduction.h), and so many holes that nearly every pixel is an
// edge pixel.
std::string BlockWithHoles(int n) {
    std::string s =
        "plane pr <1 0 0 -1>; plane pl <-1 0 0 -1>; plane pt <0 1 0 -1>; plane pb <0 -1 0 -1>;\n"
        "plane pf <0 0 1 -1>; plane pk <0 0 -1 -1>;\n";
    std::string lits = "pr pl pt pb pf pk";
    for (int i = 0; i < n; ++i) {
        const double x = std::fmod(i * 0.6180339887, 1.0) * 2 - 1, y = (i + 0.5) / n * 2 - 1;
        s += fmt::format("quadric c{} <1 1 0 0 0 0 {:.6f} {:.6f} 0 {:.8f}>;\n", i, -x, -y,
                         x * x + y * y - 1e-4);
        lits += " !c" + std::to_string(i);
    }
    return s + "body big (" + lits + ");\nview v dop 0 0 -1;\n";
}

// n balls of radius 0.3 on a 3-D grid, unioned.
std::string UnionOfSmallBalls(int n) {
    std::string s, u;
    for (int i = 0; i < n; ++i) {
        const double x = i % 20, y = (i / 20) % 20, z = i / 400;
        s += fmt::format("quadric q{} <1 1 1 0 0 0 {} {} {} {}>;\nbody b{} (q{});\n", i, -x, -y, -z,
                         x * x + y * y + z * z - 0.09, i, i);
        u += (i ? " | b" : "b") + std::to_string(i);
    }
    return s + "csg u (" + u + ");\n";
}

std::vector<BadInput> GuardAndScaleRows() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    const std::string huge = "quadric s <1e308 1e308 1e308 0 0 0 0 0 0 -1e308>;\nbody ball (s);\n";
    std::map<std::string, std::string> fanOut;  // f1 … f7 each read the next ten times: 10⁷ reads
    for (int i = 1; i < 8; ++i)
        for (int k = 0; k < 10; ++k)
            fanOut["f" + std::to_string(i) + ".uq"] += fmt::format("read \"f{}.uq\";\n", i + 1);
    fanOut["f8.uq"] = "{ empty }\n";
    fanOut["main.uq"] = "read \"f1.uq\";\n" + sphere;
    const FileText wide = Lazy([sphere] {
        std::string w;
        for (int i = 0; i < 10001; ++i) w += "read \"part.uq\";\n";
        return w + sphere;
    });
    std::string dup = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (";
    for (int i = 0; i < 2000; ++i) dup += i ? " s" : "s";
    dup += ");\n";
    const FileText balls = Lazy([] { return CoincidentBallUnion(300); });
    const FileText body = Lazy([] { return BodyOfLiterals(2000); });
    return {
        // ---- Coefficients of any magnitude: a correct, lit picture on every engine.
        {"QuadricScaledBy1e308", {{"main.uq", huge}}, "", "", "", 100},
        {"QuadricScaledBy1e308Scanline", {{"main.uq", huge}}, "--engine scanline", "", "", 100},
        {"QuadricScaledBy1e308Pixelpowers",
         {{"main.uq", huge}},
         "--engine pixelpowers",
         "",
         "",
         100},
        {"QuadricScaledBy1e308Patch", {{"main.uq", huge}}, "--engine patch", "", "", 100},
        {"QuadricScaledBy1eMinus300",
         {{"main.uq", "quadric s <1e-300 1e-300 1e-300 0 0 0 0 0 0 -1e-300>;\nbody ball (s);\n"}},
         "",
         "",
         "",
         100},
        {"PlaneScaledBy1e308",
         {{"main.uq", sphere + "plane cut <1e308 0 0 0>;\nbody half (s cut);\n"}},
         "",
         "",
         "",
         100},
        {"MixedMagnitudeBody",
         {{"main.uq",
           "quadric s <1e300 1e300 1e300 0 0 0 0 0 0 -1e300>;\nplane cut <0 1e-300 0 0>;\n"
           "body half (s cut);\n"}},
         "",
         "",
         "",
         100},
        {"EllipsoidScaledBy1e200",
         {{"main.uq", "quadric s <1e200 4e200 9e200 0 0 0 0 0 0 -1e200>;\nbody ball (s);\n"}},
         "",
         "",
         "",
         100},
        {"CappedCylinderHugePlanes",
         {{"main.uq",
           "quadric cyl <1 0 1 0 0 0 0 0 0 -1>;\nplane top <0 1e250 0 -1e250>;\n"
           "plane bot <0 1e250 0 1e250>;\nbody can (cyl top !bot);\n"}},
         "",
         "",
         "",
         100},
        // ---- Complexity guards: scenes that took minutes now draw at once, correctly.
        {"CoincidentBallsScanline", {{"main.uq", balls}}, "--engine scanline", "", "", 100},
        {"CoincidentBallsRaycast", {{"main.uq", balls}}, "", "", "", 100},
        {"CoincidentBallsPixelpowers", {{"main.uq", balls}}, "--engine pixelpowers", "", "", 100},
        {"CoincidentBallsPatch", {{"main.uq", balls}}, "--engine patch", "", "", 100},
        {"CoincidentBallsScanlineStrict",
         {{"main.uq", balls}},
         "--engine scanline --strict",
         R"(error.*cannot draw the whole scene)"},
        {"BodyOf2000Literals", {{"main.uq", body}}, "", "", "", 100},
        {"BodyOf2000LiteralsScanline", {{"main.uq", body}}, "--engine scanline", "", "", 100},
        {"BodyOf2000LiteralsPixelpowers", {{"main.uq", body}}, "--engine pixelpowers", "", "", 100},
        {"UnionOf2000SmallBalls",
         {{"main.uq", Lazy([] { return UnionOfSmallBalls(2000); })}},
         "",
         "",
         "",
         100},
        {"DuplicateLiterals", {{"main.uq", dup}}, "", "", "", 100},
        {"ReadFanOut", Files(fanOut.begin(), fanOut.end()), "",
         R"(f7\.uq:\d+:\d+: error.*more than 10000 files read)"},
        {"ReadFanOutWide",
         {{"part.uq", "{ nothing }\n"}, {"main.uq", wide}},
         "",
         R"(main\.uq:10001:\d+: error.*more than 10000 files read)"},
        // Raycast's work budget (engines/raycast/work_budget.h): a dense union past
        // max-evaluations per pixel is an error (the composing engines' too), not minutes of CPU.
        {"DenseUnionPastRaycastBudget",
         {{"main.uq", balls}},
         "--engine-opt max-evaluations=50",
         R"(error.*more than \d+ body evaluations.*max-evaluations=50.*solid 'u' has 300)"},
        // Through the reference engine too: scanline hands the union to raycast (max-overlap),
        // whose default budget (4,096 per pixel) 10,000 coincident balls pass.
        {"DenseUnionComposedByRaycast",
         {{"main.uq", Lazy([] { return CoincidentBallUnion(10000); })}},
         "--engine scanline --size 16x16",
         R"(error.*max-evaluations=4096 per pixel.*solid 'u' has 10000 operands)"},
        {"MaxEvaluationsZero",
         {{"main.uq", sphere}},
         "--engine-opt max-evaluations=0",
         R"(error.*max-evaluations)"},
        // The eye inside a solid (tests/eye_inside_test.cpp): auto-fit is an error naming it.
        {"EyeInsideSolidAutoFit",
         {{"main.uq", sphere + "view v vrp 0 0 0 vpn 0 0 1 cop 0 0 -0.5;\n"}},
         "",
         R"(main\.uq:2:1: error: the eye of view 'v' .*is inside body 'ball')"},
        {"EyeInsideSolidWithWindow",
         {{"main.uq", sphere + "view v vrp 0 0 0 vpn 0 0 1 cop 0 0 -0.5 whh 1;\n"}},
         "",
         "",
         "",
         50},
        {"EyeInsideHollowShellAutoFit",
         {{"main.uq", sphere +
                          "quadric h <1 1 1 0 0 0 0 0 0 -0.64>;\nbody hole (h);\n"
                          "csg shell (ball - hole);\nview v vrp 0 0 0 vpn 0 0 1 cop 0 0 -0.5;\n"}},
         "",
         R"(main\.uq:5:1: error: csg solid 'shell' .*(beside or behind the eye|unbounded in the view).*whh or whw)"},
        {"MaxOverlapNegative",
         {{"main.uq", sphere}},
         "--engine scanline --engine-opt max-overlap=-1",
         R"(error.*max-overlap)"},
        {"MaxOverlapNotANumber",
         {{"main.uq", sphere}},
         "--engine scanline --engine-opt max-overlap=deep",
         R"(error.*max-overlap)"},
        {"MaxLiteralsZero",
         {{"main.uq", sphere}},
         "--engine scanline --engine-opt max-literals=0",
         R"(error.*max-literals)"},
        {"BodyOf2000LiteralsPixelpowersStrict",
         {{"main.uq", body}},
         "--engine pixelpowers --strict",
         R"(error.*cannot draw the whole scene)"},
        {"PixelpowersMaxLiteralsZero",
         {{"main.uq", sphere}},
         "--engine pixelpowers --engine-opt max-literals=0",
         R"(error.*max-literals)"},
        // ---- OpenSCAD sizes are errors as in OpenSCAD; expressions and bad numbers positioned.
        {"ScadNegativeCylinderRadius",
         {{"m.scad", "cylinder(h=1, r=-1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*negative)"},
        {"ScadNegativeCylinderDiameter",
         {{"m.scad", "cylinder(h=1, d=-1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*negative)"},
        {"ScadNegativeCubeZ",
         {{"m.scad", "cube([1, 1, -1]);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*size\[2\].*positive)"},
        {"ScadZeroSphereDiameter",
         {{"m.scad", "sphere(d=0);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadZeroScale",
         {{"m.scad", "scale([1, 1, 0]) sphere(1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:\d+: error.*cannot be inverted)"},
        {"ScadNegativeCubeScalar",
         {{"m.scad", "cube(-1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadNegativeSpherePositional",
         {{"m.scad", "sphere(-2);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:1: error.*positive)"},
        {"ScadExpressionRadius",
         {{"m.scad", "sphere(r=0/0);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1:\d+: error)"},
        {"ScadOverflowingNumber",
         {{"m.scad", "translate([1e999, 0, 0]) sphere(1);\n"}},
         "{dir}/m.scad",
         R"(m\.scad:1(:\d+: error.*not a (finite )?number|: error: OpenSCAD: Parser error))"},
        // ---- Freeform models: huge knots draw lit (scale-safe normals); bad data positioned.
        {"ObjKnots1e100",
         {{"m.obj",
           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ncstype bspline\ndeg 1 1\n"
           "surf 0 1e100 0 1e100 1 2 3 4\nparm u 0 0 1e100 1e100\n"
           "parm v 0 0 1e100 1e100\nend\n"}},
         "{dir}/m.obj",
         "",
         "",
         50},
        {"ObjNanVertex",
         {{"m.obj",
           "v nan 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ncstype bezier\ndeg 1 1\n"
           "surf 0 1 0 1 1 2 3 4\nparm u 0 1\nparm v 0 1\nend\n"}},
         "{dir}/m.obj",
         R"(m\.obj:1:\d+: error.*not finite)"},
        {"ObjVertexIndexOutOfRange",
         {{"m.obj",
           "v 0 0 0\ncstype bezier\ndeg 1 1\nsurf 0 1 0 1 1 2 3 99\nparm u 0 1\n"
           "parm v 0 1\nend\n"}},
         "{dir}/m.obj",
         R"(m\.obj:4:\d+: error.*vertex index)"},
        {"ObjHugeDegree",
         {{"m.obj", "v 0 0 0\ncstype bezier\ndeg 1000000 1\nend\n"}},
         "{dir}/m.obj",
         R"(m\.obj:3:\d+: error.*degree)"},
        {"BptHugePatchCount",
         {{"m.bpt", "99999999999\n"}},
         "{dir}/m.bpt",
         R"(m\.bpt:1:\d+: error)"},
        {"BptTruncated", {{"m.bpt", "1\n3 3\n0 0 0\n"}}, "{dir}/m.bpt", R"(m\.bpt:3:\d+: error)"},
        // ---- BRL-CAD text: positioned errors.
        {"BrlcadBinaryGarbage",
         {{"m.cg", std::string("\x00\x01\x02\n", 4)}},
         "{dir}/m.cg",
         R"(m\.cg:1:1: error.*not a BRL-CAD database)"},
        {"ComgeomTruncatedDeck",
         {{"m.cg", "title\n    1    1\nrpp  1  0 1 0 1 0 1\n"}},
         "{dir}/m.cg",
         R"(m\.cg:2:\d+: error)"},
        {"V4TruncatedRecord",
         {{"m.asc", "I 1 v4\nt\nS 1 sph\n"}},
         "{dir}/m.asc",
         R"(m\.asc:3:\d+: error.*truncated)"},
        {"V5UnknownPrimitive",
         {{"m.asc", "title {t}\nput {s} frobnicate V {0 0 0}\n"}},
         "{dir}/m.asc",
         R"(m\.asc:2:\d+: error.*cannot be drawn)"},
        // ---- Command line.
        {"MaxMemoryZero", {{"main.uq", sphere}}, "--max-memory 0", R"(error.*--max-memory)"},
        {"SizeZero", {{"main.uq", sphere}}, "--size 0x0", R"(error.*size)"},
    };
}

// The front ends added by the second hardening session (issue 23): job files (`quadrix batch`),
// the viewer (`quadrix view`, offscreen), hidden-line drawings (`quadrix draw`) and exports. Each
// was tried as a user would, with wrong arguments and broken files.
std::vector<BadInput> FrontEndRows() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    const std::string broken = "body x (";
    const std::string eyeInside = sphere + "view v vrp 0 0 0 vpn 0 0 1 cop 0 0 -0.5;\n";
    auto job = [](const std::string& fields) {
        return "{\"inputs\": [\"main.uq\"], \"output\": \"out.png\", \"size\": \"16x16\"" + fields +
               "}\n";
    };
    auto batchRow = [&](const char* name, const std::string& jobs, const std::string& expect,
                        const std::string& scene) {
        BadInput b{name, {{"jobs.jsonl", jobs}, {"main.uq", scene}}, "", expect};
        b.command = "batch --quiet jobs.jsonl";
        return b;
    };
    auto row = [](const char* name, Files files, const std::string& command,
                  const std::string& expect, const std::string& setup = {}) {
        BadInput b{name, std::move(files), "", expect, setup};
        b.command = command;
        return b;
    };
    return {
        // ---- Job files: one positioned error per bad line (file:line:column for JSON syntax).
        batchRow("BatchJsonSyntaxError", "{\"inputs\": [\"main.uq\"], \"output\": \"out.png\"\n",
                 R"(jobs\.jsonl:1:\d+: invalid JSON: syntax error)", sphere),
        batchRow("BatchNumberOverflow", job(", \"az\": 1e400"),
                 R"(jobs\.jsonl:1:\d+: invalid JSON.*(overflow|out of range|too large))", sphere),
        batchRow("BatchDuplicateKey", job(", \"output\": \"other.png\""),
                 R"(jobs\.jsonl:1:\d+: the key .output. is given twice)", sphere),
        batchRow("BatchUnknownKey", job(", \"colour\": 1"), R"(jobs\.jsonl:1: unknown key)",
                 sphere),
        batchRow("BatchNotAnObject", "[1, 2]\n", R"(jobs\.jsonl:1: a job is a JSON object)",
                 sphere),
        batchRow("BatchBadSize", job(", \"size\": \"0x0\""), R"(jobs\.jsonl:1:.*size)", sphere),
        batchRow("BatchBadFrameRange", job(", \"frames\": 3, \"frame_range\": \"5:2\""),
                 R"(jobs\.jsonl:1: frame range)", sphere),
        batchRow("BatchUnknownEngine", job(", \"engine\": \"warp\""),
                 R"(jobs\.jsonl:1: unknown engine 'warp')", sphere),
        batchRow("BatchBadEngineOption", job(", \"engine_options\": {\"batch\": \"maybe\"}"),
                 R"(jobs\.jsonl:1: .*'batch' must be on or off)", sphere),
        batchRow("BatchBrokenScene", job(""), R"(main\.uq:1:9: error)", broken),
        batchRow("BatchEyeInsideSolid", job(""), R"(main\.uq:2:1: error: the eye of view 'v')",
                 eyeInside),
        batchRow("BatchDumpFrameIsTheOutput", job(", \"dump_frame\": \"out.png\""),
                 R"(cannot write 'out\.png'.*same file)", sphere),
        // "aa" takes what render's --aa takes ("default" too); a spelling it refuses is an error.
        batchRow("BatchBadAa", job(", \"aa\": \"Default\""),
                 R"(jobs\.jsonl:1: "aa" must be "off", "default", 4, 16 or 64, found "Default")",
                 sphere),
        // Outputs two jobs, or two outputs of one job, would both write: refused before anything
        // is rendered, both positions named.
        batchRow("BatchTwoJobsOneOutput", job("") + job(""),
                 R"(jobs\.jsonl:2: "output" writes 'out\.png', which job 0 \(jobs\.jsonl:1\), )"
                 R"("output", writes too)",
                 sphere),
        batchRow("BatchFrameOfAnAnimationIsAStill",
                 "{\"inputs\": [\"main.uq\"], \"output\": \"f_%d.png\", \"size\": \"16x16\", "
                 "\"frames\": 3}\n# a still picture over frame 2\n"
                 "{\"inputs\": [\"main.uq\"], \"output\": \"f_2.png\", \"size\": \"16x16\"}\n",
                 R"(jobs\.jsonl:3: "output" writes 'f_2\.png', which job 0 \(jobs\.jsonl:1\), )"
                 R"("output", frame 2, writes too)",
                 sphere),
        batchRow("BatchDumpOfAFrameIsItsPicture",
                 "{\"inputs\": [\"main.uq\"], \"output\": \"f.qxf\", \"dump_frame\": "
                 "\"f_%04d.qxf\", \"size\": \"16x16\", \"frames\": 2}\n",
                 R"(jobs\.jsonl:1: "dump_frame", frame 0, writes 'f_0000\.qxf', which this )"
                 R"(job's "output", frame 0, writes too)",
                 sphere),
        row("BatchNoJobs", {{"jobs.jsonl", "# nothing\n"}}, "batch jobs.jsonl",
            R"(error: the job file 'jobs\.jsonl' has no job)"),
        row("BatchJobFileIsDevZero", {}, "batch /dev/zero", R"(error.*larger than 256 MiB)"),
        // ---- The viewer, offscreen (no display needed).
        row("ViewBrokenScene", {{"main.uq", broken}}, "view --offscreen --bench 1 main.uq",
            R"(main\.uq:1:9: error)"),
        row("ViewUnknownEngine", {{"main.uq", sphere}},
            "view --offscreen --bench 1 --engine warp main.uq", R"(error: unknown engine 'warp')"),
        row("ViewZeroSize", {{"main.uq", sphere}}, "view --offscreen --bench 1 --size 0x0 main.uq",
            R"(error: --size.*not positive)"),
        row("ViewUnknownView", {{"main.uq", sphere}},
            "view --offscreen --bench 1 --view nope main.uq", R"(error: no view named 'nope')"),
        row("ViewBadScript", {{"main.uq", sphere}, {"s.txt", "bogus 1 2\n"}},
            "view --script s.txt main.uq", R"(s\.txt:1:1: error: unknown script event 'bogus')"),
        row("ViewMissingScript", {{"main.uq", sphere}}, "view --script none.txt main.uq",
            R"(error: --script: cannot read 'none\.txt')"),
        row("ViewEyeInsideSolid", {{"main.uq", eyeInside}}, "view --offscreen --bench 1 main.uq",
            R"(main\.uq:2:1: error: the eye of view 'v')"),
        // ---- Drawings and exports.
        row("DrawBrokenScene", {{"main.uq", broken}}, "draw main.uq -o out.svg",
            R"(main\.uq:1:9: error)"),
        row("DrawUnknownFormat", {{"main.uq", sphere}}, "draw main.uq -o out.bmp",
            R"(error: out\.bmp: the output must end in)"),
        row("DrawUnknownStandardView", {{"main.uq", sphere}},
            "draw main.uq -o out.svg --views front,nope", R"(error: unknown view 'nope')"),
        row("DrawEyeInsideSolid", {{"main.uq", eyeInside}}, "draw main.uq -o out.svg",
            R"(main\.uq:2:1: error: the eye of view 'v')"),
        row("DrawOutputIsTheScene", {{"main.uq", sphere}}, "draw main.uq -o main.svg",
            R"(cannot write.*input)", "ln main.uq main.svg"),
        // A freeform surface the drawer cannot draw: an error at its definition, not a drawing
        // silently without it (--allow-missing draws the rest; DrawCommand.Freeform*).
        row("DrawFreeformSurface",
            {{"main.uq", sphere + "bezier sq 1 1 < -1 -1 0  1 -1 0  -1 1 0  1 1 0 >;\n"}},
            "draw main.uq -o out.svg --views front,iso",
            R"(main\.uq:3:1: error: freeform surface 'sq' cannot be drawn)"),
        row("ExportBrokenScene", {{"main.uq", broken}}, "export --to pov main.uq -o out.pov",
            R"(main\.uq:1:9: error)"),
        row("ExportOutputIsTheScene", {{"main.uq", sphere}}, "export --to pov main.uq -o main.uq",
            R"(cannot write 'main\.uq': it is the input)"),
        row("ExportUnknownFormat", {{"main.uq", sphere}}, "export --to warp main.uq -o out.pov",
            R"(error: --to: warp not in)"),
        row("CompareNotAFrameDump", {{"a.qxf", "garbage"}}, "compare a.qxf a.qxf",
            R"(error: 'a\.qxf' is not a Quadrix frame dump)"),
    };
}

// Issue 23, third hardening pass: read-only targets, the shading budget, `quadrix compare`'s
// reader, the limits of every command, elongated quadrics, and the issue's reproducers that had
// only separate tests (output_safety_test.cpp, all_engines_test.cpp, complexity_guard_test.cpp).
std::vector<BadInput> ThirdPassRows() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    const FileText big = Lazy([] { return BodyOfLiterals(20000); });
    const FileText holes = Lazy([] { return BlockWithHoles(8000); });
    const FileText lit = Lazy([] { return BodyOfLiterals(20000) + "light l1 1 0 0 -1;\n"; });
    auto row = [](const char* name, Files files, const std::string& command,
                  const std::string& expect, const std::string& setup = {}) {
        BadInput b{name, std::move(files), "", expect, setup};
        b.command = command;
        return b;
    };
    auto ok = [](const char* name, Files files, const std::string& command,
                 const std::string& check, const std::string& setup = {}) {
        BadInput b{name, std::move(files), "", "", setup};
        b.command = command;
        b.check = check;
        return b;
    };
    const std::string ellipsoid = "definition d;\n" + sphere + "enddef;\n";
    const std::string aMinusA =
        "quadric unit <1 1 1 0 0 0 0 0 0 -1>; body one (unit); body two (unit);\n"
        "csg none (one - two);\nsolid box side =from 1.5 -1 -1 =to 3 1 1;\n"
        "view front dop .3 .4 -1;\n";
    return {
        // ---- A read-only target is not replaced (docs/output.md rule 1).
        {"OutputIsReadOnly",
         {{"main.uq", sphere}},
         "-o {dir}/ro.png",
         R"(cannot write.*ro\.png.*read-only \(mode 0444\))",
         "echo old > ro.png; chmod 444 ro.png"},
        {"DumpFrameIsReadOnly",
         {{"main.uq", sphere}},
         "--dump-frame {dir}/ro.qxf",
         R"(cannot write.*ro\.qxf.*read-only)",
         "echo old > ro.qxf; chmod 400 ro.qxf"},
        row("ExportOverReadOnlyFile", {{"main.uq", sphere}}, "export --to pov main.uq -o ro.pov",
            R"(cannot write 'ro\.pov'.*read-only)", "echo old > ro.pov; chmod 444 ro.pov"),
        row("DrawOverReadOnlyFile", {{"main.uq", sphere}}, "draw main.uq -o ro.svg",
            R"(cannot write.*ro\.svg.*read-only)", "echo old > ro.svg; chmod 444 ro.svg"),
        row("PipeOverReadOnlyFile", {{"p.pipe", "radius .25\npath\n0 0 0\n1 0 0\n"}},
            "pipe p.pipe -o ro.uq", R"(cannot write.*ro\.uq.*read-only)",
            "echo old > ro.uq; chmod 444 ro.uq"),
        // ---- The shading budget (shade/shade_budget.h): a body of 20,000 literals gets no
        // default anti-aliasing or shadows (a note), and asked for, a picture when the rays'
        // work stays within the budget and a clean error, not minutes, when it does not.
        // Shadow rays from the lit side leave the convex body after a few literals: within the
        // budget, a picture.
        ok("WideBodyExplicitShadows", {{"main.uq", lit}},
           "render main.uq --shadows --aa off --size 48x48 -o out.ppm", "test -s out.ppm"),
        ok("WideBodyDefaultPicture", {{"main.uq", lit}}, "render main.uq --size 48x48 -o out.ppm",
           "test -s out.ppm"),
        // The sample rays reduce each body on the rectangle of their edge pixels
        // (sample_tracer.h, Regions), as raycast does on its tiles: a convex body of 20,000
        // planes costs them a few literals each, within the budget.
        ok("WideBodyExplicitAa", {{"main.uq", big}},
           "render main.uq --aa 4 --size 48x48 -o out.ppm", "test -s out.ppm"),
        // Literals no reduction can drop, on nearly every pixel: past the budget.
        {"UnreducibleBodyExplicitAa",
         {{"main.uq", holes}},
         "--aa 4 --size 48x48",
         R"(error: anti-aliasing: the rays would evaluate more than \d+ literals.*body 'big' )"
         R"(has 8006 literals.*--aa off)"},
        // ---- quadrix compare: the bounded reader, the image limits and the memory budget.
        row("CompareDevZero", {}, "compare /dev/zero /dev/zero",
            R"(error: cannot read '/dev/zero': it is larger than 256 MiB)"),
        row("CompareHugeHeader", {{"a.qxf", "QXF1 16384 16384\n"}}, "compare a.qxf a.qxf",
            R"(a\.qxf:1:6: error: image size 16384x16384 is too large)"),
        row("CompareHeaderPastMaxMemory", {{"a.qxf", "QXF1 4096 4096\n"}},
            "compare --max-memory 100M a.qxf a.qxf",
            R"(a\.qxf:1:6: error: an image of 4096x4096 pixels needs about .*memory budget is )"
            R"(100 MiB \(--max-memory\))"),
        row("CompareBadPixelLine", {{"a.qxf", "QXF1 2 2\n0 0 1 0 0 1 0 0 0\n5 0 1 0 0 1 0 0 0\n"}},
            "compare a.qxf a.qxf", R"(a\.qxf:3:1: error: expected a pixel x in 0\.\.1)"),
        row("CompareTruncatedPixelLine", {{"a.qxf", "QXF1 2 2\n0 0 1 0 0\n"}},
            "compare a.qxf a.qxf", R"(a\.qxf:2:10: error: expected a number)"),
        // The Frame keeps one solid per body (frame/frame.h): a dump may not say otherwise.
        row("CompareBodyInTwoSolids",
            {{"a.qxf", "QXF1 2 2\n0 0 1 0 0 -1 3 7 1\n1 0 1 0 0 -1 3 7 2\n"}},
            "compare a.qxf a.qxf",
            R"(a\.qxf:3:16: error: body 7 is in solid 2 here but in solid 1 earlier)"),
        row("CompareSolidWithoutBody", {{"a.qxf", "QXF1 2 2\n0 0 1 0 0 -1 3 -1 4\n"}},
            "compare a.qxf a.qxf", R"(a\.qxf:2:16: error: solid 4 without a body)"),
        row("CompareBodyIdTooLarge", {{"a.qxf", "QXF1 2 2\n0 0 1 0 0 -1 3 2000000000 0\n"}},
            "compare a.qxf a.qxf",
            R"(a\.qxf:2:16: error: body 2000000000 or solid 0 is not an id)"),
        // ---- --max-memory and --time-limit on every command (apps/quadrix/limit_options.h):
        // a scene that is a FIFO nobody writes stalls the reader until the time limit.
        row("BatchTimeLimit",
            {{"jobs.jsonl", "{\"inputs\": [\"stall.uq\"], \"output\": \"out.png\"}\n"}},
            "batch --quiet --time-limit 0.3 jobs.jsonl", R"(error: time limit of 0\.3 s)",
            "mkfifo stall.uq"),
        row("BatchMaxMemory",
            {{"main.uq", sphere},
             {"jobs.jsonl",
              "{\"inputs\": [\"main.uq\"], \"output\": \"out.png\", \"size\": \"4096x4096\"}\n"}},
            "batch --quiet --max-memory 100M jobs.jsonl", R"(memory budget is 100 MiB)"),
        row("ViewTimeLimit", {}, "view --offscreen --bench 1 --time-limit 0.3 stall.uq",
            R"(error: time limit of 0\.3 s)", "mkfifo stall.uq"),
        row("ViewMaxMemory", {{"main.uq", sphere}},
            "view --offscreen --bench 1 --size 4096x4096 --max-memory 100M main.uq",
            R"(memory budget is 100 MiB \(--max-memory\))"),
        row("DrawTimeLimit", {}, "draw stall.uq -o out.svg --time-limit 0.3",
            R"(error: time limit of 0\.3 s)", "mkfifo stall.uq"),
        row("DrawMaxMemoryMalformed", {{"main.uq", sphere}},
            "draw main.uq -o out.svg --max-memory lots", R"(error: --max-memory.*'lots')"),
        row("ExportTimeLimit", {}, "export --to pov stall.uq -o out.pov --time-limit 0.3",
            R"(error: time limit of 0\.3 s)", "mkfifo stall.uq"),
        row("ExportTimeLimitMalformed", {{"main.uq", sphere}},
            "export --to pov main.uq -o out.pov --time-limit -2", R"(error: --time-limit)"),
        row("UqTimeLimit", {}, "uq --time-limit 0.3 -dppm:out.ppm stall.uq",
            R"(error: time limit of 0\.3 s)", "mkfifo stall.uq"),
        row("UqMaxMemoryMalformed", {{"main.uq", sphere}},
            "uq --max-memory 0 -dppm:out.ppm main.uq", R"(error: --max-memory.*'0')"),
        // ---- A quadric stretched along one axis: bounded, auto-fitted (it was "unbounded in the
        // view"); past double precision the message says why.
        {"BallScaledBy1e6",
         {{"main.uq", ellipsoid + "instance (d =sx 1e6);\nview v vpn 1 0 0 dop -1 0 0;\n"}},
         "",
         "",
         "",
         100},
        {"BallScaledBy1e6Flat",
         {{"main.uq", ellipsoid + "instance (d =sx 1e6 =sy 1e6);\n"}},
         "",
         "",
         "",
         100},
        {"BallScaledBy1e308",
         {{"main.uq", ellipsoid + "instance (d =sx 1e308);\n"}},
         "",
         R"(main\.uq:\d+:\d+: error: .*unbounded in the view \(to double precision: a quadric )"
         R"(stretched)"},
        // ---- The issue's reproducers that have separate tests, as rows too.
        ok("PipePlantedLink",
           {{"p.pipe", "radius .25\npath\n0 0 0\n1 0 0\n"}, {"victim", "precious"}},
           "pipe p.pipe -o o.uq", "test \"$(cat victim)\" = precious && grep -q quadric o.uq",
           "ln -s victim o.uq.tmp"),
        ok("ModeOf0600FileKept", {{"main.uq", sphere}}, "render main.uq --size 16x16 -o p.ppm",
           "test \"$(stat -c %a p.ppm)\" = 600 && head -c 2 p.ppm | grep -q P",
           "echo old > p.ppm; chmod 600 p.ppm"),
        {"PixelpowersGuardStrict",
         {{"main.uq", sphere + "quadric t <1 1 1 -1 0 0 0 0 0 -1>;\nbody b2 (t);\n"
                               "csg u (ball | b2);\n"}},
         "--engine pixelpowers --engine-opt max-products=1 --strict",
         R"(error.*cannot draw the whole scene)"},
        ok("PixelpowersGuardComposes",
           {{"main.uq", sphere + "quadric t <1 1 1 -1 0 0 0 0 0 -1>;\nbody b2 (t);\n"
                                 "csg u (ball | b2);\n"}},
           "render main.uq --engine pixelpowers --engine-opt max-products=1 --size 32x32 -o "
           "out.ppm --aa off",
           "{quadrix} render main.uq --size 32x32 -o ref.ppm --aa off && cmp out.ppm ref.ppm"),
        ok("PixelpowersAMinusA", {{"main.uq", aMinusA}},
           "render main.uq --engine pixelpowers --size 32x32 --aa off -o out.ppm",
           "{quadrix} render main.uq --size 32x32 --aa off -o ref.ppm && cmp out.ppm ref.ppm"),
        row("InteractiveStdinDevZero", {}, "-i < /dev/zero",
            R"(cannot read standard input: a line is longer than 256 MiB)"),
    };
}

std::vector<BadInput> Table() {
    const std::string sphere = "quadric s <1 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n";
    std::vector<BadInput> t = {
        {"MissingCloseAngle",
         {{"main.uq", "plane pl <1 0 0 1;\nbody ball (pl);\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"MissingSemicolon",
         {{"main.uq", "quadric s <1 1 1 0 0 0 0 0 0 -1>\nbody ball (s);\n"}},
         "",
         R"(main\.uq:2:\d+: error)"},
        {"UnknownHalfSpace",
         {{"main.uq", sphere + "body c (s nope);\n"}},
         "",
         R"(main\.uq:3:\d+: error.*nope)"},
        {"UnknownDefinition",
         {{"main.uq", "instance i1 (nodef =tx 1);\n"}},
         "",
         R"(main\.uq:1:\d+: error.*nodef)"},
        {"UnknownCsgOperand",
         {{"main.uq", sphere + "csg c (ball - ghost);\n"}},
         "",
         R"(main\.uq:3:\d+: error.*ghost)"},
        {"IncludeCycle",
         {{"main.uq", "read \"a.uq\";\n"},
          {"a.uq", "read \"b.uq\";\n"},
          {"b.uq", "read \"a.uq\";\n"}},
         "",
         R"(b\.uq:1:\d+: error)"},
        {"IncludeDepth17", {}, "", R"(f17\.uq:1:\d+: error|f16\.uq:1:\d+: error)"},
        {"InfiniteCoefficient",
         {{"main.uq", "quadric s <1e999 1 1 0 0 0 0 0 0 -1>;\nbody ball (s);\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"NanCoefficient",
         {{"main.uq", "plane pl <nan 0 0 1>;\nbody ball (pl);\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"ZeroQuadric",
         {{"main.uq", "quadric z <0 0 0 0 0 0 0 0 0 0>;\nbody ball (z);\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"ZeroPlaneNormal",
         {{"main.uq", "plane pl <0 0 0 1>;\nbody ball (pl);\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"UnterminatedComment",
         {{"main.uq", sphere + "{ never closed\n"}},
         "",
         R"(main\.uq:3:1: error)"},
        {"UnterminatedString", {{"main.uq", "read \"abc\n"}}, "", R"(main\.uq:1:\d+: error)"},
        {"KeywordAsId", {{"main.uq", "plane body <1 0 0 0>;\n"}}, "", R"(main\.uq:1:\d+: error)"},
        {"DuplicateId",
         {{"main.uq", sphere + "quadric s <1 1 1 0 0 0 0 0 0 -2>;\n"}},
         "",
         R"(main\.uq:3:\d+: error)"},
        {"NegativeArrayCount",
         {{"main.uq", "definition d;\n" + sphere + "enddef;\narray a1 (d) -1 =tx 1;\n"}},
         "",
         R"(main\.uq:5:\d+: error)"},
        {"ZeroScale",
         {{"main.uq", "definition d;\n" + sphere + "enddef;\ninstance (d =sx 0);\n"}},
         "",
         R"(main\.uq:5:\d+: error)"},
        {"MissingEnddef",
         {{"main.uq", "definition d;\n" + sphere}},
         "",
         R"(main\.uq:\d+:\d+: error)"},
        {"NestedDefinition",
         {{"main.uq", "definition d;\ndefinition e;\nenddef;\nenddef;\n"}},
         "",
         R"(main\.uq:2:\d+: error)"},
        {"EmptyBody", {{"main.uq", sphere + "body e ();\n"}}, "", R"(main\.uq:3:\d+: error)"},
        {"ZeroLightDirection",
         {{"main.uq", sphere + "light l1 1 0 0 0;\n"}},
         "",
         R"(main\.uq:3:\d+: error)"},
        {"DopAndCop",
         {{"main.uq", sphere + "view v dop 0 0 -1 cop 0 0 -5;\n"}},
         "",
         R"(main\.uq:3:\d+: error)"},
        {"VupParallelToVpn",
         {{"main.uq", sphere + "view v vpn 0 1 0 vup 0 2 0;\n"}},
         "",
         R"(main\.uq:3:\d+: error)"},
        {"IdStartingWithDigit",
         {{"main.uq", "plane 1abc <1 0 0 0>;\n"}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"BinaryGarbage",
         {{"main.uq", std::string("\x01\x02\xff\xfe<<>>;;\0\x7f", 12)}},
         "",
         R"(main\.uq:1:\d+: error)"},
        {"UnboundedWithoutWindow",
         {{"main.uq", "plane pl <0 1 0 0>;\nbody half (pl);\n"}},
         "",
         R"(main\.uq:2:\d+: error.*unbounded)"},
        {"EmptyScene", {{"main.uq", "{ nothing here }\n"}}, "", R"(error.*nothing to draw)"},
        {"OnlyLightsAndViews",
         {{"main.uq", "light amb .5;\nview v dop 0 0 -1;\n"}},
         "",
         R"(error.*nothing to draw)"},
        // Command-line problems: no position, still one clear line.
        {"UnknownView", {{"main.uq", sphere}}, "--view nope", R"(error.*view.*nope)"},
        {"UnknownEngine", {{"main.uq", sphere}}, "--engine warp", R"(error.*engine.*warp)"},
        {"NegativeSize", {{"main.uq", sphere}}, "--size -5x10", R"(error.*size)"},
        {"AbsurdSize", {{"main.uq", sphere}}, "--size 100000x100000", R"(error.*too large)"},
        {"MalformedSize", {{"main.uq", sphere}}, "--size big", R"(error.*size)"},
        {"UnreadableScene", {}, "{dir}/does_not_exist.uq", R"(error.*does_not_exist\.uq)"},
        {"UnwritableOutput",
         {{"main.uq", sphere}},
         "-o {dir}/no/such/dir/out.png",
         R"(error.*cannot write)"},
        {"UnknownOutputFormat", {{"main.uq", sphere}}, "-o {dir}/out.bmp", R"(error.*format)"},
    };
    for (BadInput& b : t)
        if (std::string(b.name) == "IncludeDepth17") b.files["main.uq"] = IncludeChain(17, b.files);
    for (BadInput& b : HardeningRows()) t.push_back(std::move(b));
    for (BadInput& b : AddressLimitRows()) t.push_back(std::move(b));
    for (BadInput& b : GuardAndScaleRows()) t.push_back(std::move(b));
    for (BadInput& b : FrontEndRows()) t.push_back(std::move(b));
    for (BadInput& b : ThirdPassRows()) t.push_back(std::move(b));
    return t;
}

std::string Substitute(std::string s, const std::string& dir) {
    for (std::size_t p; (p = s.find("{dir}")) != std::string::npos;) s.replace(p, 5, dir);
    return s;
}

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

std::set<std::string> Listing(const std::string& dir) {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        names.insert(entry.path().filename().string());
    return names;
}

TEST_P(BadInputTest, OneLineErrorNonZeroExitNoOutput) {
    const BadInput& b = GetParam();
    TempDir dir;
    for (const auto& [name, text] : b.files) dir.Write(name, text.Get());
    if (!b.command.empty()) {
        // Another front end: the directory must be left as the setup left it.
        if (!b.setup.empty()) {
            ASSERT_EQ(RunShell("cd '" + dir.path() + "' && " + b.setup).exitCode, 0);
        }
        const std::set<std::string> before = Listing(dir.path());
        const std::string cmd = "cd '" + dir.path() + "' && " + QuadrixBinary() + " " +
                                Substitute(b.command, dir.path());
        CommandResult r = RunShell(cmd);
        if (!b.check.empty()) {
            ASSERT_EQ(r.exitCode, 0) << cmd << "\n" << r.err;
            std::string check = Substitute(b.check, dir.path());
            for (std::size_t p; (p = check.find("{quadrix}")) != std::string::npos;)
                check.replace(p, 9, QuadrixBinary());
            const CommandResult c = RunShell("cd '" + dir.path() + "' && " + check);
            EXPECT_EQ(c.exitCode, 0) << check << "\n" << c.out << c.err;
            // No temporary file left (names the setup planted excepted).
            for (const std::string& name : Listing(dir.path())) {
                if (before.count(name)) continue;
                EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
            }
            return;
        }
        EXPECT_NE(r.exitCode, 0) << cmd << "\n" << r.err;
        EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
        // The message is searched line by line (a batch prints its failures in a summary).
        bool found = false;
        for (std::size_t pos = 0; pos < r.err.size() && !found;) {
            std::size_t end = r.err.find('\n', pos);
            if (end == std::string::npos) end = r.err.size();
            found = std::regex_search(r.err.substr(pos, end - pos), std::regex(b.expectFirstLine));
            pos = end + 1;
        }
        EXPECT_TRUE(found) << "expected /" << b.expectFirstLine << "/ in a line of stderr:\n"
                           << r.err;
        EXPECT_EQ(Listing(dir.path()), before) << cmd;
        return;
    }
    const bool picture = b.expectLitPixel > 0;
    std::string out = dir.File(picture ? "out.ppm" : "out.png");
    std::string args = Substitute(b.extraArgs, dir.path());
    std::string scene = b.files.count("main.uq") ? dir.File("main.uq") : "";
    // An explicit -o in extraArgs replaces the default output.
    bool ownOutput = args.find("-o ") != std::string::npos;
    std::string cmd =
        "cd '" + dir.path() + "' && " +
        (b.setup.empty()         ? ""
         : b.setup.back() == '|' ? b.setup + " "
                                 : b.setup + "; ") +
        QuadrixBinary() + " render " + scene + " " + args +
        (ownOutput ? "" : std::string(picture ? " --size 64x64" : "") + " -o '" + out + "'");
    CommandResult r = RunShell(cmd);
    if (picture) {
        // A correct picture: written, and lit (the sphere faces a light; a black surface or an
        // empty frame fails).
        ASSERT_EQ(r.exitCode, 0) << cmd << "\n" << r.err;
        Image image;
        ASSERT_TRUE(ReadPnm(out, image)) << cmd;
        int brightest = 0;
        for (std::uint8_t v : image.pixels) brightest = std::max(brightest, int(v));
        EXPECT_GE(brightest, b.expectLitPixel) << cmd << "\n" << r.err;
        for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
            EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
        return;
    }
    EXPECT_NE(r.exitCode, 0) << cmd << "\n" << r.err;
    EXPECT_LT(r.exitCode, 128) << "killed by a signal: " << r.err;
    // The first line that is an error (warnings, e.g. about generated ids, may come before it).
    std::string first;
    for (std::size_t pos = 0; pos < r.err.size();) {
        std::size_t end = r.err.find('\n', pos);
        std::string line =
            r.err.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
        if (line.find("error") != std::string::npos) {
            first = line;
            break;
        }
        if (end == std::string::npos) break;
        pos = end + 1;
    }
    EXPECT_TRUE(std::regex_search(first, std::regex(b.expectFirstLine)))
        << "first error line of stderr: '" << first << "'\nexpected /" << b.expectFirstLine
        << "/\nfull stderr:\n"
        << r.err;
    EXPECT_FALSE(FileExists(out));
    // No temporary files left behind either.
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

INSTANTIATE_TEST_SUITE_P(Table, BadInputTest, ::testing::ValuesIn(Table()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(BadInputTable, HasAtLeast150Entries) { EXPECT_GE(Table().size(), 150u); }

TEST(BadInputTable, HasTheHardeningRows) { EXPECT_GE(HardeningRows().size(), 70u); }

// Found by the importer fuzz targets: a BRL-CAD name holding a NUL reached the stored message
// raw. Every reader of Items() (the API's and Python's exceptions, JSON) now gets it visible.
TEST(BadInputTable, StoredMessagesHaveNoControlBytes) {
    Diagnostics d;
    d.Error({}, std::string("primitive 'a\0b\x1b[2J'", 19));
    ASSERT_EQ(d.Items().size(), 1u);
    EXPECT_EQ(d.Items()[0].message, "primitive 'a\\x00b\\x1B[2J'");
    EXPECT_EQ(d.Items()[0].message.find('\0'), std::string::npos);
}

}  // namespace
}  // namespace quadrix::testing
