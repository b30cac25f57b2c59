#!/usr/bin/python3
"""Writes a recording of a cell as `rosbag record` would have made it (launch/record_cell.launch records the
same topics): a scanner on a robot takes views of a part lying on the table, each a sensor_msgs/PointCloud2 on
the scan topic in the scanner's frame, while tf (/tf) says where the scanner is in the table's frame at 20 Hz.

  make_cell_recording.py DESIGN.stl OUT.bag [options]

The part is the design (an STL, --units) placed on the table at --xyz (m) turned --yaw (degrees) about z; the
views are --views sensors 0.4 m from the part's centre, spread round it and looking down at 56 degrees, each
seeing the design's faces that turn towards it within 75 degrees (no return from grazing faces; no occlusion),
--points surface samples a view with Gaussian noise --noise (mm). It is synthetic: a known answer for the checks.

Awkward recordings, for the replay's tests: --compression bz2|lz4; --tf none (no tf at all) or --tf-late S
(each tf message recorded S seconds after its stamp); --cloud-frame NAME (clouds whose frame tf does not know);
--repeat N (the views taken N times over, each time the same cloud: several scans, or a large bag with --points).
"""
import argparse
import bisect
import math
import os
import random
import struct

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from sensor_msgs.msg import PointCloud2, PointField
from tf2_msgs.msg import TFMessage

UNITS = {"mm": 1.0, "inch": 25.4, "m": 1000.0}


def read_stl(path, scale):
    """Triangles (three vertices, mm) of a binary or ASCII STL."""
    data = open(path, "rb").read()
    triangles = []
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * count == len(data):
            for i in range(count):
                v = struct.unpack_from("<12f", data, 84 + 50 * i)
                triangles.append([tuple(scale * c for c in v[3 + 3 * k:6 + 3 * k]) for k in range(3)])
            return triangles
    vertices = [tuple(scale * float(w) for w in line.split()[1:4])
                for line in data.decode("ascii", "replace").splitlines() if line.strip().startswith("vertex")]
    if not vertices or len(vertices) % 3:
        raise SystemExit("%s: not an STL file (neither binary nor ASCII)" % path)
    return [vertices[i:i + 3] for i in range(0, len(vertices), 3)]


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)


class Surface:
    """Area-weighted samples of the design's surface with their facet normals (design frame, mm)."""

    def __init__(self, triangles):
        self.triangles, self.normals, self.cumulative = [], [], []
        total = 0.0
        for t in triangles:
            c = cross(sub(t[1], t[0]), sub(t[2], t[0]))
            area = norm(c) / 2
            if area <= 0:
                continue
            total += area
            self.triangles.append(t)
            self.normals.append(unit(c))
            self.cumulative.append(total)
        self.total = total

    def sample(self, rng):
        i = bisect.bisect_left(self.cumulative, rng.random() * self.total)
        i = min(i, len(self.triangles) - 1)
        a, b, c = self.triangles[i]
        u, v = rng.random(), rng.random()
        if u + v > 1:
            u, v = 1 - u, 1 - v
        return tuple(a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]) for k in range(3)), self.normals[i]


def yaw_matrix(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))


def apply(m, p):
    return tuple(sum(m[r][k] * p[k] for k in range(3)) for r in range(3))


def look_at(position, target):
    """The sensor's axes (columns x, y, z) in the table frame: z along the line of sight, x level."""
    z = unit(sub(target, position))
    x = cross(z, (0.0, 0.0, 1.0))
    x = unit(x) if norm(x) > 1e-9 else (1.0, 0.0, 0.0)
    y = cross(z, x)
    return (x, y, z)


def quaternion(axes):
    """(x, y, z, w) of the rotation whose columns are the axes."""
    m = [[axes[c][r] for c in range(3)] for r in range(3)]
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = 2 * math.sqrt(t + 1)
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4)
    i = max(range(3), key=lambda k: m[k][k])
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
    q = [0.0] * 3
    q[i] = s / 4
    q[j] = (m[j][i] + m[i][j]) / s
    q[k] = (m[k][i] + m[i][k]) / s
    return (q[0], q[1], q[2], (m[k][j] - m[j][k]) / s)


def cloud_msg(points, frame, stamp):
    msg = PointCloud2()
    msg.header.frame_id = frame
    msg.header.stamp = stamp
    msg.height, msg.width = 1, len(points)
    msg.fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1) for i, n in enumerate("xyz")]
    msg.is_bigendian, msg.point_step, msg.row_step, msg.is_dense = False, 12, 12 * len(points), True
    msg.data = b"".join(struct.pack("<fff", *p) for p in points)
    return msg


def view_points(surface, rng, sensor_mm, place, offset_mm, axes, count, noise):
    """`count` samples seen from the sensor, in the sensor's frame (m)."""
    points = []
    cos_limit = math.cos(math.radians(75))
    tries = 0
    while len(points) < count and tries < 50 * count:
        tries += 1
        p, n = surface.sample(rng)
        p = tuple(a + b for a, b in zip(apply(place, p), offset_mm))
        n = apply(place, n)
        to_sensor = sub(sensor_mm, p)
        if dot(n, to_sensor) < cos_limit * norm(to_sensor):
            continue
        p = tuple(c + rng.gauss(0, noise) for c in p)
        d = sub(p, sensor_mm)
        points.append(tuple(dot(d, axes[k]) / 1000 for k in range(3)))
    return points


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("design")
    ap.add_argument("out")
    ap.add_argument("--units", default="mm", choices=sorted(UNITS))
    ap.add_argument("--xyz", default="0.1,0.05,0", help="where the design's origin lies on the table (m)")
    ap.add_argument("--yaw", type=float, default=30.0, help="the design's turn about the table's z (degrees)")
    ap.add_argument("--views", type=int, default=3)
    ap.add_argument("--points", type=int, default=15000)
    ap.add_argument("--noise", type=float, default=0.02, help="mm, 1-sigma per axis")
    ap.add_argument("--topic", default="/scan/points")
    ap.add_argument("--fixed-frame", default="table")
    ap.add_argument("--scanner-frame", default="scanner")
    ap.add_argument("--cloud-frame", default="", help="the clouds' frame_id (default: the scanner's)")
    ap.add_argument("--tf", default="dynamic", choices=["dynamic", "none"])
    ap.add_argument("--tf-late", type=float, default=0.0, help="s each tf message is recorded after its stamp")
    ap.add_argument("--compression", default="none", choices=["none", "bz2", "lz4"])
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()

    rng = random.Random(a.seed)
    surface = Surface(read_stl(a.design, UNITS[a.units]))
    offset = tuple(1000 * float(v) for v in a.xyz.split(","))
    place = yaw_matrix(a.yaw)
    lo = [min(apply(place, v)[k] for t in surface.triangles for v in t) for k in range(3)]
    hi = [max(apply(place, v)[k] for t in surface.triangles for v in t) for k in range(3)]
    centre = tuple((l + h) / 2 + o for l, h, o in zip(lo, hi, offset))
    sensors = []
    for i in range(a.views):
        turn = 2 * math.pi * i / a.views + 0.3
        d = unit((math.cos(turn), math.sin(turn), 1.5))
        sensors.append(tuple(c + 400 * k for c, k in zip(centre, d)))
    period = 2.0  # s the robot holds each view; the cloud comes half way
    start = 1.0
    clouds = []  # each view's cloud, taken again as it was on a repeat (a large bag is written in seconds)
    with rosbag.Bag(a.out, "w", compression=a.compression) as bag:
        for r in range(a.repeat):
            for i, sensor in enumerate(sensors):
                k = r * len(sensors) + i
                t0 = start + k * period
                axes = look_at(sensor, centre)
                q = quaternion(axes)
                if a.tf == "dynamic":
                    for step in range(int(period * 20)):
                        stamp = rospy.Time.from_sec(t0 + step / 20.0)
                        tf = TransformStamped()
                        tf.header.stamp, tf.header.frame_id, tf.child_frame_id = stamp, a.fixed_frame, a.scanner_frame
                        tf.transform.translation.x, tf.transform.translation.y, tf.transform.translation.z = (
                            c / 1000 for c in sensor)
                        (tf.transform.rotation.x, tf.transform.rotation.y, tf.transform.rotation.z,
                         tf.transform.rotation.w) = q
                        bag.write("/tf", TFMessage(transforms=[tf]), rospy.Time.from_sec(t0 + step / 20.0 + a.tf_late))
                stamp = rospy.Time.from_sec(t0 + period / 2)
                if r == 0:
                    clouds.append(cloud_msg(view_points(surface, rng, sensor, place, offset, axes, a.points, a.noise),
                                            a.cloud_frame or a.scanner_frame, stamp))
                cloud = clouds[i]
                cloud.header.stamp = stamp
                bag.write(a.topic, cloud, stamp)
    print("%s: %d views of %s at %s m turned %g deg, %d bytes (%s)" % (
        a.out, a.views * a.repeat, os.path.basename(a.design), a.xyz, a.yaw, os.path.getsize(a.out), a.compression))


if __name__ == "__main__":
    main()
