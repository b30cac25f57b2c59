#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpus (test/fuzz/corpus/<target>/) from test/data, config/ and small hand-made
inputs. The seeds are committed; run again only to change them. Kept small: libFuzzer mutates short inputs faster."""
import gzip
import pathlib
import struct

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "test" / "data"
OUT = ROOT / "test" / "fuzz" / "corpus"


def put(target, name, content):
    folder = OUT / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(content if isinstance(content, bytes) else content.encode())


def ascii_head(path, facets):
    """The first `facets` facets of an ASCII STL, closed again."""
    lines = path.read_text(errors="replace").splitlines(keepends=True)
    out, count = [], 0
    for line in lines:
        out.append(line)
        if line.strip().startswith("endfacet"):
            count += 1
            if count == facets:
                break
    out.append("endsolid\n")
    return "".join(out)


def binary_head(path, triangles):
    """The header and the first `triangles` records of a binary STL, the count set to match."""
    raw = path.read_bytes()
    return raw[:80] + struct.pack("<I", triangles) + raw[84:84 + 50 * triangles]


TETRA = [((0, 0, -1), [(0, 0, 0), (0, 1, 0), (1, 0, 0)]), ((0, -1, 0), [(0, 0, 0), (1, 0, 0), (0, 0, 1)]),
         ((-1, 0, 0), [(0, 0, 0), (0, 0, 1), (0, 1, 0)]), ((0.577, 0.577, 0.577), [(1, 0, 0), (0, 1, 0), (0, 0, 1)])]


def tetra_ascii(newline="\n"):
    s = "solid tetra" + newline
    for n, corners in TETRA:
        s += "  facet normal %g %g %g%s    outer loop%s" % (*n, newline, newline)
        for c in corners:
            s += "      vertex %g %g %g%s" % (*c, newline)
        s += "    endloop%s  endfacet%s" % (newline, newline)
    return s + "endsolid tetra" + newline


def tetra_binary(header=b"tetra"):
    body = b"".join(struct.pack("<12fH", *n, *[x for c in corners for x in c], 0) for n, corners in TETRA)
    return header.ljust(80, b" ") + struct.pack("<I", len(TETRA)) + body


def stl():
    put("stl_ascii", "failedinpycam_head.stl", ascii_head(DATA / "failedinpycam.stl", 12))
    put("stl_ascii", "wheel_in_box_head.stl", ascii_head(DATA / "wheel_in_box.stl", 8))
    put("stl_ascii", "tetra.stl", tetra_ascii())
    put("stl_ascii", "tetra_crlf.stl", tetra_ascii("\r\n"))
    put("stl_ascii", "two_solids.stl", tetra_ascii() + tetra_ascii().replace("tetra", "second"))
    put("stl_binary", "featuretype_head.stl", binary_head(DATA / "featuretype.STL", 12))
    put("stl_binary", "ktoolcav_head.stl", binary_head(DATA / "ktoolcav.stl", 12))  # header starts with "solid"
    put("stl_binary", "mount_rush_head.stl", binary_head(DATA / "mount_rush.stl", 16))
    put("stl_binary", "tetra.stl", tetra_binary())
    put("stl_binary", "tetra_solid_header.stl", tetra_binary(b"solid tetra exported by a CAD system"))
    put("stl_binary", "tetra.stl.gz", gzip.compress(tetra_binary(), mtime=0))


def cloud():
    put("cloud", "bunny.pcd", (DATA / "pcl_bunny.pcd").read_bytes())
    put("cloud", "milk_binary_compressed.pcd", (DATA / "pcl_milk.pcd").read_bytes())
    header = ("# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 4\nHEIGHT 1\n"
              "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\n")
    points = [(0, 0, 0), (0.01, 0, 0), (0, 0.01, 0.002), (float("nan"), 0, 0)]
    put("cloud", "four_ascii.pcd", header + "DATA ascii\n" + "".join("%g %g %g\n" % p for p in points))
    put("cloud", "four_binary.pcd", header.encode() + b"DATA binary\n" +
        b"".join(struct.pack("<3f", *p) for p in points))
    organised = header.replace("WIDTH 4\nHEIGHT 1", "WIDTH 2\nHEIGHT 2").replace("FIELDS x y z", "FIELDS x y z")
    put("cloud", "organised_double.pcd", organised.replace("SIZE 4 4 4", "SIZE 8 8 8").encode() + b"DATA binary\n" +
        b"".join(struct.pack("<3d", *p) for p in points))
    put("cloud", "wavy_mesh.ply", (DATA / "noether_wavy_mesh_with_hole.ply").read_bytes())
    ply = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 2\nproperty list uchar int vertex_indices\nend_header\n")
    put("cloud", "square_ascii.ply", ply + "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
    binary = ply.replace("format ascii", "format binary_little_endian").replace("float", "double")
    put("cloud", "square_binary.ply", binary.encode() + b"".join(struct.pack("<3d", *p) for p in
        [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]) + b"".join(struct.pack("<B3i", 3, *f) for f in [(0, 1, 2), (0, 2, 3)]))


GCODE = {
    "lines.ngc": "%\n(rosmill raster)\nG21 G90 G17 G54\nT1 M6\nS10000 M3\nG0 Z5\nG0 X0 Y0\nG1 Z-1 F300\n"
                 "G1 X10 Y0 F1200\nX10 Y5\nX0\nG0 Z5\nM5\nM30\n%\n",
    "arcs.ngc": "G21 G90 G17\nG0 X0 Y0 Z2\nG1 Z-1 F200\nG2 X10 Y0 I5 J0 F600\nG3 X0 Y0 R5\nG91.1\n"
                "G2 X0 Y0 I5 J0 Z-2 P2\nG18 G2 X5 Z-1 I2.5 K0\nG17 G90.1 G3 X0 Y0 I2.5 J0\nM2\n",
    "inch_incremental.ngc": "N10 G20 G91 G17 ; relative inches\nN20 G0 X1 Y1 Z0.2\nN30 G1 Z-0.3 F10\n"
                            "N40 X 1 . 5 Y-0.5\n/N50 X2\nN60 G90 G21 G0 Z10\nN70 M30\n",
    "offsets.ngc": "G21 G90\nG55 G0 X1 Y1 Z1\nG43 H1 G1 Z0 F100\nG49\nG10 L2 P1 X0\nG28\nG92 X0\nG53 G0 Z0\n"
                   "M8 M9 S500 M4\nG93 G1 X2 F1\nG94\nM30\n",
}


def gcode():
    for name, text in GCODE.items():
        put("gcode", name, text)


TOOLPATH = ('{"format":"rosmill-toolpath","version":1,"units":"mm","toolpaths":[{"strategy":"raster",'
            '"tool":{"id":2,"name":"ball 6","type":"ball","diameter":6,"corner_radius":3,"flute_length":20,'
            '"shank_diameter":6,"spindle_rpm":12000,"feed":1500,"plunge_feed":400,"stepover":1,"stepdown":2},'
            '"safe_z":10,"clearance_z":5,"start":[0,0,10],"passes":[{"name":"row 1","moves":[[0,0,10,0,0],'
            '[0,0,1,2,400],[10,0,1,1,1500],[10,5,1.5,1,1500],[10,5,10,0,0]]}]}]}')


def toolpath():
    put("toolpath_json", "raster.json", TOOLPATH)
    two = TOOLPATH.replace(']}]}]}', ']}]},' + TOOLPATH[TOOLPATH.index('{"strategy"'):-2] + ']}')
    put("toolpath_json", "two_tools.json", two)


def job():
    for f in sorted((ROOT / "config" / "jobs").glob("*.yaml")):
        put("job_yaml", f.name, f.read_bytes())
    put("job_yaml", "flow_style.yaml", "{part: 'primitive:cone', units: inch, stock: {mesh: 'primitive:cylinder'}, "
        "operations: [{strategy: waterline, tool: 'bull:6:1', setup: -X, tolerance: 0.01}]}\n")


def tables():
    for selector, name in enumerate(["tools.yaml", "presets.yaml", "machine.yaml"]):
        put("tables", name, bytes([selector]) + (ROOT / "config" / name).read_bytes())


def grbl():
    put("grbl", "run_to_end.txt", "ok\nok\n<Run|MPos:0.000,0.000,5.000|FS:0,0|Ln:3>\n"
        "ok\nok\nok\n<Hold:0|MPos:10.000,5.000,-1.000|FS:300,1000>\nok\nok\nok\n<Idle|WPos:1,2,3|FS:0,0>\n")
    put("grbl", "error_then_alarm.txt", "ok\nerror:20\nok\nALARM:2\n<Alarm|MPos:1.5,2.5,3.5>\nerror:9\n")
    put("grbl", "reset.txt", "ok\nok\nGrbl 1.1f ['$' for help]\n<Idle|MPos:0,0,0|Ln:99>\n")


def linuxcnc():
    handshake = ("HELLO ACK EMCNETSVR 1.1\r\nSET VERBOSE ACK\r\nSET ENABLE ACK\r\nSET SET_WAIT ACK\r\n"
                 "SET TIMEOUT ACK\r\nSET ESTOP ACK\r\nSET WAIT ACK\r\nSET MACHINE ACK\r\nSET WAIT ACK\r\n")
    start = ("ERROR OK\r\nSET MODE ACK\r\nSET WAIT ACK\r\nSET OPEN ACK\r\nSET WAIT ACK\r\nERROR OK\r\n"
             "SET RUN ACK\r\n")
    poll = "PROGRAM_STATUS {}\r\nPROGRAM_LINE {}\r\nABS_ACT_POS 1.0 2.0 3.0 0 0 0\r\nERROR {}\r\n"
    put("linuxcnc", "run_to_end.txt", handshake + start + poll.format("RUNNING", 2, "OK") +
        poll.format("PAUSED", 3, "OK") + poll.format("IDLE", 7, "OK"))
    put("linuxcnc", "refused.txt", handshake.replace("SET MACHINE ACK", "SET MACHINE NAK"))
    put("linuxcnc", "error_while_running.txt", handshake + start + poll.format("RUNNING", 4, "joint 0 limit"))


def ros_convert():
    put("ros_convert", "mesh.bin", bytes([0]) + bytes(range(1, 200)))
    put("ros_convert", "cloud.bin", bytes([1, 3, 0, 0, 0, 0, 1, 1, 0]) + struct.pack("<6f", 0, 0, 0, 1, 1, 1))
    put("ros_convert", "job.bin", bytes([2, 1]) + bytes(range(50, 250)))


if __name__ == "__main__":
    stl()
    cloud()
    gcode()
    toolpath()
    job()
    tables()
    grbl()
    linuxcnc()
    ros_convert()
