difference() {
  cube([2, 2, 2], center=true);
  translate([0, 0, 1]) cylinder(h=3, r1=0.5, r2=0.8, center=true, $fn=64);
  rotate([90, 0, 0]) sphere(d=1.5);
}
multmatrix([[1,0,0,1],[0,1,0,0],[0,0,1,0],[0,0,0,1]]) intersection() { sphere(1); cube(1.5, center=true); }
