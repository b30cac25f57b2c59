// An L bracket: a base plate 60 x 40 x 8 and a wall 8 thick, 40 tall at +X, with a groove 4 high, 2 deep across
// most of the wall's +X face (its ends stop 5 mm short of the wall's sides).
$fn = 32;
difference() {
  union() {
    cube([60, 40, 8]);
    translate([52, 0, 0]) cube([8, 40, 40]);
  }
  translate([58, 5, 20]) cube([3, 30, 4]);
}
