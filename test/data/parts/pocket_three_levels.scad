// 60 x 40 x 20 mm block with a pocket [10, 50] x [8, 32], 14 mm deep (floor at z 6) round a round island 10 mm
// across at (30, 20): three levels for a step-down of 5.
difference() {
  cube([60, 40, 20]);
  difference() {
    translate([10, 8, 6]) cube([40, 24, 15]);
    translate([30, 20, 0]) cylinder(d = 10, h = 21, $fn = 72);
  }
}
