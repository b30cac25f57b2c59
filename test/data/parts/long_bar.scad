// A bar 180 x 40 x 30 mm, too long to stand on its end under the default machine's spindle, with a pocket on top
// and a blind hole 8 mm across and 10 mm deep in its +X end (reachable only along X).
$fn = 32;
difference() {
  cube([180, 40, 30]);
  translate([40, 10, 24]) cube([100, 20, 7]);
  translate([181, 20, 15]) rotate([0, -90, 0]) cylinder(d = 8, h = 11);
}
