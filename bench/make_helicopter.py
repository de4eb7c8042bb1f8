#!/usr/bin/env python3
"""Writes a synthetic helicopter as a BRL-CAD v5 ASCII database (issue 20 item 5).

The helicopter model of issue 20 ("2,400 primitives: 3.4 s flatten, 0.07 s render") is not among
the shared samples, so this generator makes a stand-in with the structure of a real vehicle
database (FORMAT.md §3): regions of 3-20 primitives combined by union, intersection and
subtraction; combinations nested up to six deep (all.g > helicopter > main_rotor > blade_assy >
bolt_ring > bolt.r > primitive); and sub-assemblies referenced many times with different matrices
(five main blades, four tail blades scaled down through m15, six wheels, rings and rows of the
same bolt, four rocket pods, a frame rib repeated along the boom). Only quadric/planar
primitives (arb8, tgc with similar ends, ell), so every engine can draw it.

Deterministic (no randomness). Usage:

    bench/make_helicopter.py OUT.asc [--rows N]

--rows sets the rows of fuselage rivets (24 bolts of 3 primitives each per row): 20 (the
default) gives about 2,200 primitive instances, 130 about 10,000. Render with
`quadrix render OUT.asc --top all.g --az 35 --el 25 --stats`.
"""

import argparse
import math


def fmt(x):
    return "%.17g" % x


def vec(v):
    return "{%s %s %s}" % (fmt(v[0]), fmt(v[1]), fmt(v[2]))


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(a[0] ** 2 + a[1] ** 2 + a[2] ** 2)
    return (a[0] / n, a[1] / n, a[2] / n)


class Db:
    def __init__(self):
        self.lines = ["title {Synthetic helicopter (Quadrix bench, issue 20)}", "units mm"]
        self.primitives = 0

    def put(self, text):
        self.lines.append(text)

    def tgc(self, name, v, h, r1, r2=None):
        """A right circular cylinder (r2 = r1) or cone frustum from v along h."""
        r2 = r1 if r2 is None else r2
        hn = unit(h)
        helper = (1, 0, 0) if abs(hn[0]) < 0.9 else (0, 1, 0)
        a = unit(cross(hn, helper))
        b = unit(cross(hn, a))
        self.put("put {%s} tgc V %s H %s A %s B %s C %s D %s" % (
            name, vec(v), vec(h), vec(scale(a, r1)), vec(scale(b, r1)), vec(scale(a, r2)),
            vec(scale(b, r2))))
        self.primitives += 1

    def ell(self, name, v, a, b, c):
        self.put("put {%s} ell V %s A %s B %s C %s" % (name, vec(v), vec(a), vec(b), vec(c)))
        self.primitives += 1

    def box(self, name, centre, half, yaw=0.0, pitch=0.0):
        """An arb8 box, rotated by yaw about z, then pitch about y (oblique faces)."""
        cy, sy, cp, sp = math.cos(yaw), math.sin(yaw), math.cos(pitch), math.sin(pitch)

        def place(p):
            x, y, z = p
            x, z = cp * x + sp * z, -sp * x + cp * z
            x, y = cy * x - sy * y, sy * x + cy * y
            return add(centre, (x, y, z))

        hx, hy, hz = half
        corners = [(-hx, -hy, -hz), (hx, -hy, -hz), (hx, hy, -hz), (-hx, hy, -hz),
                   (-hx, -hy, hz), (hx, -hy, hz), (hx, hy, hz), (-hx, hy, hz)]
        self.put("put {%s} arb8 %s" % (
            name, " ".join("V%d %s" % (i + 1, vec(place(c))) for i, c in enumerate(corners))))
        self.primitives += 1

    def comb(self, name, tree, region=False, rgb=None, region_id=None):
        self.put("put {%s} comb region %s tree %s" % (name, "yes" if region else "no", tree))
        if region or rgb:
            attrs = []
            if region:
                attrs += ["{region} {R}", "{region_id} {%d}" % (region_id or 1000)]
            if rgb:
                attrs.append("{rgb} {%d/%d/%d}" % rgb)
            self.put("attr set {%s} %s" % (name, " ".join(attrs)))


def leaf(name, m=None):
    if m is None:
        return "{l %s}" % name
    return "{l %s {%s}}" % (name, " ".join(fmt(x) for x in m))


def op(o, *items):
    """A left-deep binary tree of `o` over items (v5 trees are binary)."""
    t = items[0]
    for x in items[1:]:
        t = "{%s %s %s}" % (o, t, x)
    return t


def matrix(rot_z=0.0, rot_x=0.0, rot_y=0.0, t=(0, 0, 0), inv_scale=1.0):
    """Row-major 4x4: rotation Rz·Ry·Rx, then translation; m15 = inverse uniform scale."""
    def rz(a):
        c, s = math.cos(a), math.sin(a)
        return [[c, -s, 0], [s, c, 0], [0, 0, 1]]

    def rx(a):
        c, s = math.cos(a), math.sin(a)
        return [[1, 0, 0], [0, c, -s], [0, s, c]]

    def ry(a):
        c, s = math.cos(a), math.sin(a)
        return [[c, 0, s], [0, 1, 0], [-s, 0, c]]

    def mul(p, q):
        return [[sum(p[i][k] * q[k][j] for k in range(3)) for j in range(3)] for i in range(3)]

    r = mul(rz(rot_z), mul(ry(rot_y), rx(rot_x)))
    return [r[0][0], r[0][1], r[0][2], t[0], r[1][0], r[1][1], r[1][2], t[1],
            r[2][0], r[2][1], r[2][2], t[2], 0, 0, 0, inv_scale]


def build(rows):
    db = Db()
    grey, dark, olive, glass = (150, 150, 155), (60, 60, 65), (85, 95, 60), (120, 160, 190)

    # A bolt: a region of 3 primitives, (head ∪ shank) − socket, along +z from the origin.
    db.tgc("bolt.head", (0, 0, 0), (0, 0, 6), 9)
    db.tgc("bolt.shank", (0, 0, -30), (0, 0, 30), 5)
    db.tgc("bolt.socket", (0, 0, 2), (0, 0, 5), 4)
    db.comb("bolt.r", op("-", op("u", leaf("bolt.head"), leaf("bolt.shank")),
                         leaf("bolt.socket")), region=True, rgb=dark, region_id=2001)
    # Rings of 8 bolts (radius 60) and rows of 24 bolts (pitch 50).
    db.comb("bolt_ring", op("u", *[leaf("bolt.r", matrix(t=(60 * math.cos(k * math.pi / 4),
                                                            60 * math.sin(k * math.pi / 4), 0)))
                                   for k in range(8)]))
    db.comb("bolt_row", op("u", *[leaf("bolt.r", matrix(t=(50 * k, 0, 0))) for k in range(24)]))

    # A rotor blade: a region of 8 primitives along +x (spar box ∩ airfoil ellipsoid, tip, root
    # fitting minus two lightening holes, a trim tab cut by a slanted box).
    db.box("blade.spar", (3600, 0, 0), (3400, 260, 60))
    db.ell("blade.foil", (3600, 0, 0), (3500, 0, 0), (0, 280, 0), (0, 0, 45))
    db.ell("blade.tip", (7000, 0, 0), (120, 0, 0), (0, 200, 0), (0, 0, 35))
    db.tgc("blade.root", (0, 0, -70), (0, 0, 140), 180)
    db.tgc("blade.hole1", (90, 0, -80), (0, 0, 160), 25)
    db.tgc("blade.hole2", (-90, 0, -80), (0, 0, 160), 25)
    db.box("blade.tab", (6200, -280, 0), (300, 60, 12), yaw=0.05)
    db.box("blade.tabcut", (6450, -330, 0), (120, 40, 30), yaw=0.6)
    db.comb("blade.r", op("u", op("n", leaf("blade.spar"), leaf("blade.foil")), leaf("blade.tip"),
                          op("-", leaf("blade.root"), leaf("blade.hole1"), leaf("blade.hole2")),
                          op("-", leaf("blade.tab"), leaf("blade.tabcut"))),
            region=True, rgb=dark, region_id=2002)
    db.comb("blade_assy", op("u", leaf("blade.r"), leaf("bolt_ring", matrix(t=(0, 0, 70)))))

    # Rotor hub: a region of 10 primitives, plus a ring of bolts; main rotor = hub + 5 blades.
    db.tgc("hub.body", (0, 0, -150), (0, 0, 300), 420)
    db.tgc("hub.cap", (0, 0, 150), (0, 0, 120), 300, 120)
    db.tgc("hub.mast", (0, 0, -900), (0, 0, 760), 140)
    for k in range(5):
        a = 2 * math.pi * k / 5
        db.box("hub.arm%d" % k, (420 * math.cos(a), 420 * math.sin(a), 0), (220, 110, 90), yaw=a)
    db.tgc("hub.bore", (0, 0, 100), (0, 0, 200), 60)
    db.tgc("hub.swash", (0, 0, -520), (0, 0, 80), 380)
    db.comb("hub.r", op("-", op("u", leaf("hub.body"), leaf("hub.cap"), leaf("hub.mast"),
                                *[leaf("hub.arm%d" % k) for k in range(5)], leaf("hub.swash")),
                        leaf("hub.bore")), region=True, rgb=grey, region_id=2003)
    db.comb("main_rotor", op("u", leaf("hub.r"), leaf("bolt_ring", matrix(t=(0, 0, 150))),
                             *[leaf("blade_assy", matrix(rot_z=2 * math.pi * k / 5 + 0.2,
                                                         t=(420 * math.cos(2 * math.pi * k / 5 + 0.2),
                                                            420 * math.sin(2 * math.pi * k / 5 + 0.2), 0)))
                               for k in range(5)]))
    # Tail rotor: the same blade assembly, four times, scaled to 0.22 (m15 = 1/0.22), in the
    # x-z plane.
    db.comb("tail_rotor", op("u", *[leaf("blade_assy", matrix(rot_x=math.pi / 2, rot_y=math.pi / 2 * k,
                                                              inv_scale=1 / 0.22))
                                    for k in range(4)]))

    # Fuselage: cabin (ellipsoid cut by boxes minus windows), boom, fin, stabiliser, frames.
    db.ell("cab.shell", (0, 0, 0), (4200, 0, 0), (0, 1300, 0), (0, 0, 1400))
    db.ell("cab.inner", (0, 0, 0), (4100, 0, 0), (0, 1200, 0), (0, 0, 1300))
    db.box("cab.floor", (0, 0, -1200), (4500, 1500, 300))
    db.box("cab.nosecut", (4300, 0, -900), (600, 1500, 500), pitch=0.5)
    for k in range(6):
        db.box("cab.win%d" % k, (2600 - 900 * k, 1250 if k % 2 else -1250, 400), (300, 200, 250),
               pitch=0.15 * k)
    db.comb("cabin.r", op("-", leaf("cab.shell"), leaf("cab.inner"), leaf("cab.floor"),
                          leaf("cab.nosecut"), *[leaf("cab.win%d" % k) for k in range(6)]),
            region=True, rgb=olive, region_id=2010)
    db.ell("canopy.e", (2800, 0, 900), (1500, 0, 0), (0, 1000, 0), (0, 0, 700))
    db.box("canopy.cut", (2800, 0, 400), (1600, 1100, 500))
    db.comb("canopy.r", op("-", leaf("canopy.e"), leaf("canopy.cut")), region=True, rgb=glass,
            region_id=2011)
    db.tgc("boom.outer", (-3800, 0, 300), (-6500, 0, 500), 650, 260)
    db.tgc("boom.inner", (-3790, 0, 300), (-6520, 0, 500), 600, 220)
    db.comb("boom.r", op("-", leaf("boom.outer"), leaf("boom.inner")), region=True, rgb=olive,
            region_id=2012)
    db.box("fin.box", (-10000, 0, 1300), (600, 60, 1100), pitch=-0.35)
    db.ell("fin.ell", (-10000, 0, 1300), (900, 0, 0), (0, 80, 0), (0, 0, 1300))
    db.box("stab.box", (-9400, 0, 700), (400, 1400, 40), yaw=0.1)
    db.ell("stab.ell", (-9400, 0, 700), (500, 0, 0), (0, 1500, 0), (0, 0, 60))
    db.comb("tail.r", op("u", op("n", leaf("fin.box"), leaf("fin.ell")),
                         op("n", leaf("stab.box"), leaf("stab.ell"))),
            region=True, rgb=olive, region_id=2013)
    # A frame rib (6 primitives), repeated 14 times along the cabin and boom, scaled down aft.
    db.ell("rib.outer", (0, 0, 0), (40, 0, 0), (0, 1290, 0), (0, 0, 1390))
    db.ell("rib.inner", (0, 0, 0), (60, 0, 0), (0, 1180, 0), (0, 0, 1280))
    db.box("rib.floor", (0, 0, -1250), (80, 1400, 300))
    db.tgc("rib.hole1", (-50, 600, 800), (100, 0, 0), 90)
    db.tgc("rib.hole2", (-50, -600, 800), (100, 0, 0), 90)
    db.box("rib.slot", (0, 0, 1200), (100, 200, 60), yaw=0.3)
    db.comb("rib.r", op("-", leaf("rib.outer"), leaf("rib.inner"), leaf("rib.floor"),
                        leaf("rib.hole1"), leaf("rib.hole2"), leaf("rib.slot")),
            region=True, rgb=grey, region_id=2014)
    ribs = []
    for k in range(14):
        x = 3200 - 600 * k
        s = 1.0 if x > -3000 else max(0.25, 1 - (-3000 - x) / 8000)
        ribs.append(leaf("rib.r", matrix(t=(x, 0, 0 if s == 1 else 300), inv_scale=1 / s)))
    db.comb("frames", op("u", *ribs))
    # Rivet rows: `rows` rows of 24 bolts along the cabin sides, at different heights and angles.
    rivets = [leaf("bolt_row", matrix(rot_x=(0.35 + 0.4 * (k // 2) / max(1, rows)) * (1 if k % 2 else -1) + (math.pi / 2 if k % 2 else -math.pi / 2),
                                      t=(-3000 + 37 * (k % 7), 1250 if k % 2 else -1250,
                                         -300 + 1000 * (k // 2) / max(1, rows // 2))))
              for k in range(rows)]
    db.comb("rivets", op("u", *rivets))
    db.comb("fuselage", op("u", leaf("cabin.r"), leaf("canopy.r"), leaf("boom.r"), leaf("tail.r"),
                           leaf("frames"), leaf("rivets")))

    # Landing gear: a wheel (6 primitives) with a ring of bolts, struts, six wheels.
    db.tgc("wheel.tyre", (0, -110, 0), (0, 220, 0), 330)
    db.tgc("wheel.well", (0, -120, 0), (0, 240, 0), 210)
    db.tgc("wheel.rim", (0, -100, 0), (0, 200, 0), 215)
    db.tgc("wheel.rimcut", (0, -90, 0), (0, 180, 0), 150)
    db.tgc("wheel.hub", (0, -130, 0), (0, 260, 0), 80)
    db.tgc("wheel.axle", (0, -200, 0), (0, 400, 0), 30)
    db.comb("wheel.r", op("u", op("-", leaf("wheel.tyre"), leaf("wheel.well")),
                          op("-", leaf("wheel.rim"), leaf("wheel.rimcut")),
                          op("-", leaf("wheel.hub"), leaf("wheel.axle"))),
            region=True, rgb=dark, region_id=2020)
    db.comb("wheel_assy", op("u", leaf("wheel.r"),
                             leaf("bolt_ring", matrix(rot_x=-math.pi / 2, t=(0, 130, 0),
                                                      inv_scale=1 / 1.6))))
    db.tgc("strut.leg", (0, 0, 0), (0, 0, 900), 70)
    db.box("strut.brace", (0, 0, 450), (40, 300, 40), yaw=0.0, pitch=0.4)
    db.comb("strut.r", op("u", leaf("strut.leg"), leaf("strut.brace")), region=True, rgb=grey,
            region_id=2021)
    db.comb("gear", op("u", leaf("strut.r"), leaf("wheel_assy", matrix(t=(0, -260, 0))),
                       leaf("wheel_assy", matrix(rot_z=math.pi, t=(0, 260, 0)))))
    db.comb("landing_gear", op("u", leaf("gear", matrix(t=(3000, 0, -2100))),
                               leaf("gear", matrix(t=(-1200, 1300, -2100))),
                               leaf("gear", matrix(t=(-1200, -1300, -2100)))))

    # Weapons: a rocket pod (a region of 20: a tube minus 19 launch tubes), four pods on pylons.
    db.tgc("pod.body", (-900, 0, 0), (1800, 0, 0), 260)
    db.tgc("pod.nose", (900, 0, 0), (200, 0, 0), 260, 150)
    tubes = []
    for k in range(18):
        ring, i = (1, k) if k < 6 else (2, k - 6)
        n = 6 if ring == 1 else 12
        r = 85 if ring == 1 else 185
        a = 2 * math.pi * i / n
        name = "pod.tube%d" % k
        db.tgc(name, (-1000, r * math.cos(a), r * math.sin(a)), (2300, 0, 0), 34)
        tubes.append(leaf(name))
    db.tgc("pod.tube_c", (-1000, 0, 0), (2300, 0, 0), 34)
    db.comb("pod.r", op("-", op("u", leaf("pod.body"), leaf("pod.nose")), leaf("pod.tube_c"),
                        *tubes), region=True, rgb=olive, region_id=2030)
    db.box("pylon.box", (0, 0, 0), (500, 700, 60))
    db.ell("pylon.ell", (0, 0, 0), (700, 0, 0), (0, 900, 0), (0, 0, 80))
    db.box("pylon.cut", (0, 0, -60), (200, 100, 80), yaw=0.7)
    db.comb("pylon.r", op("-", op("n", leaf("pylon.box"), leaf("pylon.ell")), leaf("pylon.cut")),
            region=True, rgb=olive, region_id=2031)
    db.comb("stub_wing", op("u", leaf("pylon.r"), leaf("pod.r", matrix(t=(0, 350, -320))),
                            leaf("pod.r", matrix(t=(0, -350, -320)))))
    db.comb("weapons", op("u", leaf("stub_wing", matrix(t=(300, 1900, -300))),
                          leaf("stub_wing", matrix(rot_z=math.pi, t=(300, -1900, -300)))))

    # Cockpit: two seats (5 boxes each) and an instrument panel with 30 knobs (2 primitives).
    db.box("seat.pan", (0, 0, 0), (250, 250, 40))
    db.box("seat.back", (-260, 0, 350), (40, 250, 380), pitch=0.2)
    db.box("seat.armL", (0, 270, 150), (200, 20, 100))
    db.box("seat.armR", (0, -270, 150), (200, 20, 100))
    db.box("seat.base", (0, 0, -200), (150, 150, 160))
    db.comb("seat.r", op("u", leaf("seat.pan"), leaf("seat.back"), leaf("seat.armL"),
                         leaf("seat.armR"), leaf("seat.base")), region=True, rgb=dark,
            region_id=2040)
    db.tgc("knob.body", (0, 0, 0), (30, 0, 0), 18)
    db.tgc("knob.pointer", (28, 0, 0), (8, 0, 0), 6, 3)
    db.comb("knob.r", op("u", leaf("knob.body"), leaf("knob.pointer")), region=True, rgb=grey,
            region_id=2041)
    db.box("panel.board", (0, 0, 0), (30, 700, 220), pitch=0.3)
    db.comb("panel.r", leaf("panel.board"), region=True, rgb=dark, region_id=2042)
    knobs = [leaf("knob.r", matrix(t=(30, -560 + 80 * (k % 15), -100 + 200 * (k // 15))))
             for k in range(30)]
    db.comb("panel", op("u", leaf("panel.r"), *knobs))
    db.comb("cockpit", op("u", leaf("seat.r", matrix(t=(2400, 0, -700))),
                          leaf("seat.r", matrix(t=(1200, 0, -500))),
                          leaf("panel", matrix(t=(3300, 0, 100)))))

    db.comb("helicopter", op("u", leaf("fuselage"), leaf("cockpit"), leaf("landing_gear"),
                             leaf("weapons"), leaf("main_rotor", matrix(t=(0, 0, 2300))),
                             leaf("tail_rotor", matrix(t=(-10300, 220, 1900)))))
    db.comb("all.g", leaf("helicopter"))
    return db


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--rows", type=int, default=20)
    args = ap.parse_args()
    db = build(args.rows)
    with open(args.out, "w") as f:
        f.write("\n".join(db.lines) + "\n")


if __name__ == "__main__":
    main()
