// A 70 x 50 x 35 mm block with features on five sides (the bottom, -Z, is held).
$fn = 48;
difference() {
  cube([70, 50, 35]);
  // top: a pocket 30 x 20, 6 deep, with a round island of 8 mm diameter left standing in it
  difference() {
    translate([10, 15, 29]) cube([30, 20, 7]);
    translate([25, 25, 28]) cylinder(d = 8, h = 8);
  }
  // top: a step along +X end, 10 wide, 5 down
  translate([60, -1, 30]) cube([11, 52, 6]);
  // -X side: a slot 20 (along Y) x 8 (along Z), 8 deep into X
  translate([-1, 15, 12]) cube([9, 20, 8]);
  // +Y side: two blind holes, 8 mm diameter, 10 deep
  translate([20, 51, 15]) rotate([90, 0, 0]) cylinder(d = 8, h = 11);
  translate([45, 51, 15]) rotate([90, 0, 0]) cylinder(d = 8, h = 11);
  // +X side: a groove 6 wide (along Z), 3 deep, across the whole side (along Y)
  translate([67, -1, 10]) cube([4, 52, 6]);
}
