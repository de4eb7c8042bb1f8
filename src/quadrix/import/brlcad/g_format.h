// The BRL-CAD binary database, format v5 (".g"): the layout shared by g_reader.cpp and
// g_writer.cpp. FORMAT.md (shared/data/brlcad) covers the ASCII dumps only; this is the binary
// form of the same objects, as BRL-CAD's db5 format documentation describes it.
//
// A .g file is a sequence of objects, each a multiple of 8 bytes long. Every integer is big-endian
// ("network order"), every real an IEEE-754 double, big-endian.
//
//   byte 0      magic1 0x76 ('v')
//   byte 1      hflags: bits 0-1 DLI (0 application object, 1 header object, 2 free storage),
//               bit 2 hidden, bits 3-4 name-length width code, bit 5 name present,
//               bits 6-7 object-length width code
//   byte 2      aflags: bits 0-2 compression (0 = none), bit 5 attributes present, bits 6-7 width
//   byte 3      bflags: the same for the body
//   byte 4, 5   major type (1 BRL-CAD geometry, 2 attributes only, 9/10 binary data), minor type
//   ...         object length in 8-byte units (width code w: 1, 2, 4 or 8 bytes = 1 << w)
//   [name]      length (name width), bytes including the final NUL
//   [attrs]     length (attribute width), then name NUL value NUL ... and one more NUL
//   [body]      length (body width), then the body
//   pad         zeros up to the last byte of the object, magic2 0x35 ('5')
//
// The file starts with the header object 76 01 00 00 00 00 01 35 (the "v5 magic bytes"), then the
// attribute-only object _GLOBAL (title, units = millimetres per display unit,
// regionid_colortable = "{low high r g b} ...").
//
// Bodies of the BRL-CAD geometry types (minor type = librt's ID number; lengths in mm):
//   tor 1: V H(unit) r_a r_h                  tgc 2 (rec 7): V H A B C D
//   ell 3 (sph 10): V A B C                   arb8 4: the 8 vertices
//   half 6: N d (inside N·P <= d)             arbn 14: u32 n, then n × (a b c d), a x+b y+c z = d
//   part 16: V H r_v r_h                      rpc 17: V H B r          rhc 18: V H B r c
//   epa 19: V H A(unit) r_1 r_2               ehy 20: V H A(unit) r_1 r_2 c
//   eto 21: V N C r r_d                       hyp 38: V H A b bnr
//   pipe 15: u32 n, then n × (x y z, inner diameter, outer diameter, bend radius)
//   ars 5: u32 curves, u32 points per curve, then curves × points × (x y z)
//   bot 30: u32 nv, u32 nf, u8 orientation, u8 mode, u8 flags, nv × xyz, nf × 3 u32,
//           in plate modes nf thicknesses and the face-mode bit vector as a hex string + NUL,
//           with flag 0x1 (surface normals) u32 nn, u32 nfn, nn × xyz, nfn × 3 u32
//   comb 31: u8 width code w, then nmat, nleaf, leafbytes, rpn_len, max_stack_depth (w bytes
//           each), nmat × 16 doubles (row-major), nleaf × (name NUL, signed matrix index, w
//           bytes, -1 = identity), and rpn_len bytes of postfix tokens (1 leaf, 2 union,
//           3 intersection, 4 difference, 5 xor, 6 not). rpn_len = 0: the union of the leaves,
//           paired into a balanced tree. The region flag, ids and colour are attributes:
//           region (R/P/V), region_id, aircode, material_id, los, rgb "r/g/b", shader/oshader,
//           inherit.
#pragma once

#include <cstdint>
#include <string_view>

namespace quadrix::import::brlcad::g5 {

inline constexpr unsigned char kMagic1 = 0x76, kMagic2 = 0x35;
inline constexpr unsigned char kHeader[8] = {0x76, 0x01, 0x00, 0x00, 0x00, 0x00, 0x01, 0x35};

inline constexpr int kMajorGeometry = 1, kMajorAttributeOnly = 2;

inline constexpr int kDliApplication = 0, kDliHeader = 1, kDliFree = 2;
inline constexpr unsigned char kNamePresent = 0x20, kSectionPresent = 0x20;

enum CombToken : unsigned char {
    kTokLeaf = 1,
    kTokUnion = 2,
    kTokIntersect = 3,
    kTokSubtract = 4,
    kTokXor = 5,
    kTokNot = 6
};

// librt's ID numbers (the minor types of major type 1), by name.
struct MinorType {
    int id;
    std::string_view name;
};
inline constexpr MinorType kMinorTypes[] = {
    {1, "tor"},       {2, "tgc"},       {3, "ell"},       {4, "arb8"},    {5, "ars"},
    {6, "half"},      {7, "rec"},       {8, "poly"},      {9, "bspline"}, {10, "sph"},
    {11, "nmg"},      {12, "ebm"},      {13, "vol"},      {14, "arbn"},   {15, "pipe"},
    {16, "part"},     {17, "rpc"},      {18, "rhc"},      {19, "epa"},    {20, "ehy"},
    {21, "eto"},      {22, "grip"},     {23, "joint"},    {24, "hf"},     {25, "dsp"},
    {26, "sketch"},   {27, "extrude"},  {28, "submodel"}, {29, "cline"},  {30, "bot"},
    {31, "comb"},     {35, "superell"}, {36, "metaball"}, {37, "brep"},   {38, "hyp"},
    {39, "constrnt"}, {40, "revolve"},  {41, "pnts"},     {42, "annot"},  {43, "hrt"},
    {44, "datum"},    {45, "script"},   {46, "material"}};

inline constexpr int kComb = 31;

// 0, 1, 2, 3 → 1, 2, 4, 8 bytes.
inline constexpr int WidthBytes(int code) { return 1 << code; }

// The smallest width code that holds v (BRL-CAD's db5_select_length_encoding).
inline int WidthCodeFor(std::uint64_t v) {
    if (v <= 0xff) return 0;
    if (v <= 0xffff) return 1;
    if (v <= 0xffffffffull) return 2;
    return 3;
}

}  // namespace quadrix::import::brlcad::g5
