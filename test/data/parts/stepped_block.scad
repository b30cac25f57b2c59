// A 40 x 30 x 21 mm block with a step at -X (8 wide, 7 down, across the whole side) and a round boss on top
// (8 across, 4 high) off the centre: no turn maps it onto itself, so a scan of it registers to one pose, and a
// 6 mm end mill finishes everything from above (no inner vertical corner). The replay's recordings
// (test/ros/make_cell_recording.py) scan it.
$fn = 48;
difference() {
  cube([40, 30, 21]);
  translate([-1, -1, 14]) cube([9, 32, 8]);
}
translate([30, 20, 21]) cylinder(d = 8, h = 4);
