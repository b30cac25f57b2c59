// A 40 x 30 x 25 mm block for 3+2 on the trunnion: a pocket on top, a slot through the -Y side, a blind hole in
// +X and a step at -X.
$fn = 32;
difference() {
  cube([40, 30, 25]);
  translate([12, 8, 19]) cube([16, 14, 7]);                 // pocket 16 x 14, 6 deep
  translate([14, -1, 8]) cube([12, 9, 7]);                   // slot in -Y: 12 wide, 7 high, 8 deep
  translate([41, 15, 12]) rotate([0, -90, 0]) cylinder(d = 8, h = 11);  // blind hole in +X, 10 deep
  translate([-1, -1, 18]) cube([7, 32, 8]);                  // step at -X: 6 wide, 7 down
}
