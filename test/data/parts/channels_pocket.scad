// 80 x 60 x 20 mm block with a pocket [10, 70] x [10, 50], 12 mm deep (floor at z 8), and three islands standing
// to the block's top, each leaving a gap to a pocket wall sized for a 5 mm end mill:
//   a round island 10 mm across centred at (30, 39): a channel 6 mm wide (1.2 D) to the +Y wall;
//   a round island 8 mm across centred at (59, 34): a channel 7 mm wide (1.4 D) to the +X wall;
//   a square island [42, 56] x [14, 26]: a gap 4 mm wide (narrower than the tool) to the -Y wall.
difference() {
  cube([80, 60, 20]);
  difference() {
    translate([10, 10, 8]) cube([60, 40, 13]);
    translate([30, 39, 0]) cylinder(d = 10, h = 21, $fn = 72);
    translate([59, 34, 0]) cylinder(d = 8, h = 21, $fn = 72);
    translate([42, 14, 0]) cube([14, 12, 21]);
  }
}
