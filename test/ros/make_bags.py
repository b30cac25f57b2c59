#!/usr/bin/python3
"""Writes the recorded bags of the rostests (test/data/bags/) with the rosbag API.

  test/ros/make_bags.py [OUT_DIR] [SHARED_DATA_DIR]

Each bag holds sensor_msgs/PointCloud2 messages on /scan/points (metres, REP 103), stamped from t = 1 s:
  dome_scan.bag      the seed dome (r 50 mm on z = 0) sampled on a 2 mm grid as a scanner above it sees it, in
                     the frame `scanner`, which the tests place 0.3 m above the workpiece origin looking down
                     (rotated 180 deg about X)
  bunny_scan.bag     PCL's bunny (a real scan, ASCII PCD) in the frame `workpiece`
  empty_cloud.bag    a cloud with no points
  lost_frame.bag     the dome cloud in a frame `nowhere` that no transform reaches
  part_scan.bag      a real part scanned in a robot cell (scan_n_plan_workshop's part_scan.ply, 3,627 points,
                     metres) in the cell's frame `cell`, 0.57-1.03 m away from its origin, as the scanner saw it
The files are small (< 200 kB) and committed; run this again only when the content should change.
"""
import math
import os
import struct
import sys

import rosbag
import rospy
from sensor_msgs.msg import PointCloud2, PointField

TOPIC = "/scan/points"


def cloud_msg(points, frame, stamp):
    msg = PointCloud2()
    msg.header.frame_id = frame
    msg.header.stamp = stamp
    msg.height = 1
    msg.width = len(points)
    msg.fields = [PointField(name=n, offset=4 * i, datatype=PointField.FLOAT32, count=1) for i, n in enumerate("xyz")]
    msg.is_bigendian = False
    msg.point_step = 12
    msg.row_step = 12 * len(points)
    msg.is_dense = True
    msg.data = b"".join(struct.pack("<fff", *p) for p in points)
    return msg


def dome_points_in_scanner():
    """Dome r = 50 mm seen from above on a 2 mm grid, in the scanner frame (m)."""
    pts = []
    r = 0.050
    n = int(r / 0.002)
    for i in range(-n, n + 1):
        for j in range(-n, n + 1):
            x, y = i * 0.002, j * 0.002
            if x * x + y * y > r * r:
                continue
            z = math.sqrt(max(r * r - x * x - y * y, 0.0))
            # workpiece -> scanner: the scanner sits at z = 0.3 m looking down (180 deg about X)
            pts.append((x, -y, 0.3 - z))
    return pts


def read_ascii_pcd(path):
    pts, data = [], False
    with open(path) as f:
        for line in f:
            if data:
                v = line.split()
                if len(v) >= 3:
                    pts.append(tuple(float(c) for c in v[:3]))
            elif line.startswith("DATA"):
                if "ascii" not in line:
                    raise SystemExit(path + ": only ASCII PCD is read here")
                data = True
    return pts


def read_binary_ply_vertices(path):
    """The x, y, z of the vertices of a binary little-endian PLY (the other vertex properties are skipped)."""
    sizes = {"char": 1, "uchar": 1, "short": 2, "ushort": 2, "int": 4, "uint": 4, "float": 4, "double": 8}
    formats = {"float": "f", "double": "d"}
    with open(path, "rb") as f:
        if f.readline().strip() != b"ply":
            raise SystemExit(path + ": not a PLY file")
        count, props, in_vertex = 0, [], False
        while True:
            words = f.readline().decode("ascii").split()
            if not words:
                continue
            if words[0] == "format" and words[1] != "binary_little_endian":
                raise SystemExit(path + ": only binary_little_endian PLY is read here")
            if words[0] == "element":
                in_vertex = words[1] == "vertex"
                if in_vertex:
                    count = int(words[2])
            elif words[0] == "property" and in_vertex:
                props.append((words[2], words[1]))
            elif words[0] == "end_header":
                break
        stride = sum(sizes[t] for _, t in props)
        offsets, at = {}, 0
        for name, t in props:
            offsets[name] = (at, t)
            at += sizes[t]
        data = f.read(stride * count)
    pts = []
    for i in range(count):
        base = i * stride
        pts.append(tuple(struct.unpack_from("<" + formats[offsets[c][1]], data, base + offsets[c][0])[0] for c in "xyz"))
    return pts


def write(path, clouds):
    with rosbag.Bag(path, "w") as bag:
        for i, (points, frame) in enumerate(clouds):
            stamp = rospy.Time(1 + i)
            bag.write(TOPIC, cloud_msg(points, frame, stamp), stamp)
    print("%s: %d message(s), %d bytes" % (path, len(clouds), os.path.getsize(path)))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "data", "bags")
    shared = sys.argv[2] if len(sys.argv) > 2 else os.path.join(here, "..", "..", "..", "shared", "data")
    os.makedirs(out, exist_ok=True)
    dome = dome_points_in_scanner()
    write(os.path.join(out, "dome_scan.bag"), [(dome, "scanner")])
    write(os.path.join(out, "bunny_scan.bag"), [(read_ascii_pcd(os.path.join(shared, "cloud", "pcl_bunny.pcd")), "workpiece")])
    write(os.path.join(out, "empty_cloud.bag"), [([], "workpiece")])
    write(os.path.join(out, "lost_frame.bag"), [(dome, "nowhere")])
    write(os.path.join(out, "part_scan.bag"),
          [(read_binary_ply_vertices(os.path.join(shared, "cloud", "snp_part_scan.ply")), "cell")])


if __name__ == "__main__":
    main()
