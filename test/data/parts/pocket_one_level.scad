// 60 x 40 x 10 mm block with a pocket [10, 50] x [8, 32], 4 mm deep (floor at z 6) round a round island 10 mm
// across at (30, 20): one level for a step-down of 5.
difference() {
  cube([60, 40, 10]);
  difference() {
    translate([10, 8, 6]) cube([40, 24, 5]);
    translate([30, 20, 0]) cylinder(d = 10, h = 11, $fn = 72);
  }
}
