#!/usr/bin/python3
# Agreement catalogue (issue 23, item 7): writes small valid base scenes, one
# per family, and one-defect variants of them into OUTDIR, with the tiny
# asset files they name (OBJ meshes, URDF and MJCF robots) and a manifest.
#
#   /usr/bin/python3 tests/agreement/gen-catalogue.py OUTDIR
#
# Scene names are <family>_<defect>.rscene; <family>_ok.rscene is the family's
# base (a control every tool must accept).  OUTDIR/manifest.tsv lists, one
# line a scene: name, the scene line the defect is on (0 for a control), the
# family, and what the defect is.  Standard library only; deterministic.

import os
import sys

HEADER = [
    "raisim_engine_scene 1",
    "time_step 0.001",
    "gravity 0 0 -9.81",
    "material mat_a 0.7 0.3 0.2 1 0 0.6 0 0 0 0 false - - - - - - id=mat_a",
    "group /World id=folder_world parentId=- visible=true locked=false expanded=true",
    "light /World/Sun -0.4 0.5 -1 3 id=light_sun parentGroupId=folder_world type=directional color=1,1,1",
    "camera /World/Cam -4 0 2 0.9659258 0 0.2588190 0 50 0.05 50 64 48 rgb true id=camera_main parentGroupId=folder_world outputPath=cam.png",
    "object /World/Ground ground 0 0 0 1 0 0 0 10 10 1 1 0 0 default mat_a false true true - static true 1 18446744073709551615 id=object_ground parentGroupId=folder_world",
]
ALL = "18446744073709551615"


def box(path, ident, x, y, z, extra=""):
    return (f"object {path} box {x} {y} {z} 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default mat_a false true false - "
            f"dynamic true 1 {ALL} id={ident} parentGroupId=folder_world{extra}")


# ---------------------------------------------------------------- assets
def cloth_obj(n=4, step=0.1):
    v = [f"v {i * step:g} {j * step:g} 0" for j in range(n) for i in range(n)]
    f = []
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i + 1
            f.append(f"f {a} {a + 1} {a + n + 1}")
            f.append(f"f {a} {a + n + 1} {a + n}")
    return "\n".join(["# 4 x 4 cloth"] + v + f) + "\n"


CUBE_OBJ = """# unit cube
v -0.5 -0.5 -0.5
v 0.5 -0.5 -0.5
v 0.5 0.5 -0.5
v -0.5 0.5 -0.5
v -0.5 -0.5 0.5
v 0.5 -0.5 0.5
v 0.5 0.5 0.5
v -0.5 0.5 0.5
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
"""

ASSETS = {
    "cube.obj": CUBE_OBJ,
    "cloth.obj": cloth_obj(),
    "junk.obj": "this is not a mesh \x01\x02\n{}\n",
    "badidx.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
    "nofaces.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\n",
    "nanv.obj": "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
    "tex.png": None,  # written as a real 1x1 PNG below
    "junk.png": "not a png\n",
}


def png_1x1():
    import struct
    import zlib

    def chunk(t, d):
        c = struct.pack(">I", len(d)) + t + d
        return c + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    ihdr = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
    idat = zlib.compress(b"\x00\xff\x80\x00")
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


# A floating-base arm: base box, two revolute joints.  gc 7 + 2, gv 6 + 2.
def inertial(mass="1", i="0.01"):
    return (f'<inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="{mass}"/>'
            f'<inertia ixx="{i}" ixy="0" ixz="0" iyy="{i}" iyz="0" izz="{i}"/></inertial>')


def urdf(base_mass="2", base_inertia="0.02", j1_type="revolute", j1_axis="0 1 0", j1_parent="base",
         j2_origin="0 0 0.3", upper_geom='<box size="0.1 0.1 0.3"/>', extra="", j2_child="lower",
         upper_link="upper", lower_col='<box size="0.1 0.1 0.3"/>', limit='lower="-1" upper="1"'):
    return f"""<?xml version="1.0"?>
<robot name="arm">
  <link name="base">
    {inertial(base_mass, base_inertia)}
    <visual><geometry><box size="0.3 0.3 0.2"/></geometry></visual>
    <collision><geometry><box size="0.3 0.3 0.2"/></geometry></collision>
  </link>
  <joint name="j1" type="{j1_type}">
    <parent link="{j1_parent}"/>
    <child link="upper"/>
    <origin xyz="0 0 0.2" rpy="0 0 0"/>
    <axis xyz="{j1_axis}"/>
    <limit {limit} effort="10" velocity="5"/>
  </joint>
  <link name="{upper_link}">
    {inertial()}
    <visual><geometry>{upper_geom}</geometry></visual>
    <collision><geometry>{upper_geom}</geometry></collision>
  </link>
  <joint name="j2" type="revolute">
    <parent link="upper"/>
    <child link="{j2_child}"/>
    <origin xyz="{j2_origin}" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/>
  </joint>
  <link name="lower">
    {inertial()}
    <visual><geometry><box size="0.1 0.1 0.3"/></geometry></visual>
    <collision><geometry>{lower_col}</geometry></collision>
  </link>
{extra}</robot>
"""


# A fixed-base MJCF arm: two hinges.  gc 2, gv 2.
def mjcf(model_attr="", body1_extra="", geom2='<geom name="g2" type="capsule" fromto="0 0 0 0 0 0.3" size="0.04"/>',
         joint1='<joint name="h1" type="hinge" axis="0 1 0"/>', tail="", inner=""):
    return f"""<mujoco model="arm"{model_attr}>
  <compiler angle="radian"/>
  <worldbody>
    <body name="link1" pos="0 0 0.5"{body1_extra}>
      {joint1}
      <geom name="g1" type="capsule" fromto="0 0 0 0 0 0.3" size="0.05"/>
      <body name="link2" pos="0 0 0.3">
        <joint name="h2" type="hinge" axis="0 1 0"/>
        {geom2}
{inner}      </body>
    </body>
  </worldbody>
{tail}</mujoco>
"""


# ---------------------------------------------------------------- families
# Each family: base lines (after HEADER unless it replaces it) and defects.
# A defect is (name, target, op, *args[, files]); target is a substring of
# the base line to change (None for ops that need none).
#   ("key", k, v, ...) set key k to v on the target line (append if absent);
#                      more k, v pairs may follow
#   ("pos", i, v)      set token i (the tag is token 0)
#   ("line", text)     replace the target line
#   ("add", text)      append a line at the end (the defect line)
#   ("move", t)        move the target line before the first line containing t
# An optional last element {relpath: text} writes extra asset files.

FAMILIES = {}


def family(name, lines, defects, header=True):
    FAMILIES[name] = ((HEADER if header else []) + lines, defects)


# -- world: header, physics singletons, lexical errors
family("world", [
    "solver 80 1e-07 0.2 accurate defaultFriction=0.8 defaultRestitution=0",
    box("/World/Box", "object_box", 0, 0, 0.2),
], [
    ("version3", "raisim_engine_scene", "line", "raisim_engine_scene 3"),
    ("noheader", "raisim_engine_scene", "line", "# no header"),
    ("dt0", "time_step", "line", "time_step 0"),
    ("dtneg", "time_step", "line", "time_step -0.001"),
    ("dthuge", "time_step", "line", "time_step 2"),
    ("dtnan", "time_step", "line", "time_step nan"),
    ("dtword", "time_step", "line", "time_step fast"),
    ("dtextra", "time_step", "line", "time_step 0.001 0.002"),
    ("gravity_huge", "gravity", "line", "gravity 0 0 -1e13"),
    ("gravity_short", "gravity", "line", "gravity 0 -9.81"),
    ("gravity_inf", "gravity", "line", "gravity 0 0 -inf"),
    ("solver_iter_huge", "solver 80", "pos", 1, "20000"),
    ("solver_iter_frac", "solver 80", "pos", 1, "8.5"),
    ("solver_friction_neg", "solver 80", "key", "defaultFriction", "-1"),
    ("solver_restitution_huge", "solver 80", "key", "defaultRestitution", "1e16"),
    ("pct_bad", "object /World/Box", "pos", 1, "/World/B%G1x"),
    ("ctrl_char", "object /World/Box", "pos", 1, "/World/B\x01x"),
    ("nul_byte", "object /World/Box", "pos", 1, "/World/B\x00x"),
    ("bad_utf8", "object /World/Box", "pos", 1, "/World/B\udcffx"),
    ("pos_after_key", "object /World/Box", "line",
     "object /World/Box box id=object_box 0 0 0.2 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default mat_a false true false - dynamic true 1 " + ALL),
    ("key_without_name", "object /World/Box", "key", "", "1"),
])

# -- obj: objects and compounds
OBJ_LINES = [
    box("/World/Box", "object_box", 0, 0, 0.2),
    f"object /World/Ball sphere 1 0 0.3 1 0 0 0 1 1 1 0.2 0 1 default mat_a false true false - dynamic true 1 {ALL} id=object_ball parentGroupId=folder_world",
    f"object /World/Pill capsule -1 0 0.3 1 0 0 0 1 1 1 0.1 0.3 1 default mat_a false true false - dynamic true 1 {ALL} id=object_pill parentGroupId=folder_world",
    f"object /World/Can cylinder 0 1 0.3 1 0 0 0 1 1 1 0.1 0.3 1 default mat_a false true false - dynamic true 1 {ALL} id=object_can parentGroupId=folder_world",
    f"object /World/Mesh mesh 0 -1 0.5 1 0 0 0 0.3 0.3 0.3 0 0 1 default mat_a false true false assets/cube.obj dynamic true 1 {ALL} id=object_mesh parentGroupId=folder_world",
    "compound /World/Cart 1 1 0.5 1 0 0 0 1 1 1 5 dynamic true true id=compound_cart parentGroupId=folder_world",
    "compound_child /World/Cart box 0 0 0 1 0 0 0 1 1 1 size=0.6,0.4,0.1 contactMaterial=default material=mat_a",
    "compound_child /World/Cart sphere 0.2 0 0.1 1 0 0 0 1 1 1 radius=0.08 contactMaterial=default",
]
family("obj", OBJ_LINES, [
    ("box_mass0", "/World/Box box", "pos", 15, "0"),
    ("box_massneg", "/World/Box box", "pos", 15, "-1"),
    ("box_masshuge", "/World/Box box", "pos", 15, "1e20"),
    ("box_masstiny", "/World/Box box", "pos", 15, "1e-320"),
    ("box_massnan", "/World/Box box", "pos", 15, "nan"),
    ("box_scale0", "/World/Box box", "pos", 11, "0"),
    ("box_scaleneg", "/World/Box box", "pos", 11, "-0.4"),
    ("box_scalehuge", "/World/Box box", "pos", 11, "1e13"),
    ("box_posnan", "/World/Box box", "pos", 3, "nan"),
    ("box_poshuge", "/World/Box box", "pos", 3, "1e13"),
    ("box_quat0", "/World/Box box", "line", OBJ_LINES[0].replace(" 0.2 1 0 0 0 ", " 0.2 0 0 0 0 ")),
    ("box_prim_bad", "/World/Box box", "pos", 2, "blob"),
    ("box_mode_bad", "/World/Box box", "pos", 22, "floating"),
    ("box_group_neg", "/World/Box box", "pos", 24, "-1"),
    ("box_visible_bad", "/World/Box box", "pos", 19, "maybe"),
    ("box_fields_short", "/World/Box box", "line",
     "object /World/Box box 0 0 0.2 1 0 0 0 0.4 0.4 0.4 0.5 1 1 default mat_a false id=object_box"),
    ("box_material_unknown", "/World/Box box", "pos", 17, "mat_nope"),
    ("box_parent_unknown", "/World/Box box", "key", "parentGroupId", "folder_nope"),
    ("box_dup_path", None, "add", box("/World/Box", "object_box2", 2, 2, 0.2)),
    ("box_dup_id", None, "add", box("/World/Box2", "object_ball", 2, 2, 0.2)),
    ("box_inertia_neg", "/World/Box box", "key", "customInertia", "true inertiaDiagonal=-1,1,1"),
    ("box_inertia_huge", "/World/Box box", "key", "customInertia", "true inertiaDiagonal=1e16,1,1"),
    ("sphere_r0", "/World/Ball sphere", "pos", 13, "0"),
    ("sphere_rneg", "/World/Ball sphere", "pos", 13, "-0.2"),
    ("capsule_hneg", "/World/Pill capsule", "pos", 14, "-0.3"),
    ("cylinder_rhuge", "/World/Can cylinder", "pos", 13, "1e13"),
    ("mesh_nopath", "/World/Mesh mesh", "pos", 21, "-"),
    ("mesh_missing", "/World/Mesh mesh", "pos", 21, "assets/nope.obj"),
    ("mesh_junk", "/World/Mesh mesh", "pos", 21, "assets/junk.obj"),
    ("mesh_nofaces", "/World/Mesh mesh", "pos", 21, "assets/nofaces.obj"),
    ("mesh_badidx", "/World/Mesh mesh", "pos", 21, "assets/badidx.obj"),
    ("mesh_dir", "/World/Mesh mesh", "pos", 21, "assets"),
    ("compound_mass0", "compound /World/Cart", "pos", 12, "0"),
    ("compound_quat0", "compound /World/Cart", "line",
     "compound /World/Cart 1 1 0.5 0 0 0 0 1 1 1 5 dynamic true true id=compound_cart parentGroupId=folder_world"),
    ("compound_inertia_neg", "compound /World/Cart", "key", "inertiaDiagonal", "-1,1,1"),
    ("compound_mode_bad", "compound /World/Cart", "pos", 13, "floating"),
    ("child_ground", "compound_child /World/Cart box", "pos", 2, "ground"),
    ("child_size0", "compound_child /World/Cart box", "key", "size", "0,0.4,0.1"),
    ("child_sizehuge", "compound_child /World/Cart box", "key", "size", "1e13,0.4,0.1"),
    ("child_rneg", "compound_child /World/Cart sphere", "key", "radius", "-0.08"),
    ("child_orphan", None, "add", "compound_child /World/Nope box 0 0 0 1 0 0 0 1 1 1 size=0.1,0.1,0.1"),
    ("child_quat0", "compound_child /World/Cart box", "line",
     "compound_child /World/Cart box 0 0 0 0 0 0 0 1 1 1 size=0.6,0.4,0.1 contactMaterial=default material=mat_a"),
])

# -- gran: granular
GRAN = ("granular /World/Sand sand 0 0 0.1 1 0 0 0 1 1 1 id=granular_sand parentGroupId=folder_world "
        "boxMin=0,0,0 boxMax=0.13,0.13,0.09 radius=0.02 spacing=0.043 maxParticles=1000 density=1600 "
        "normalStiffness=5e4 normalDamping=25 tangentialStiffness=2.5e4 tangentialDamping=6 friction=0.8 "
        "rollingFriction=0.02 cohesionStiffness=0 cohesionMaxDistance=0 normalContactModel=linear substeps=2")
G = "granular /World/Sand"
family("gran", [GRAN], [
    ("radius0", G, "key", "radius", "0"),
    ("radiusneg", G, "key", "radius", "-0.02"),
    ("radiusnan", G, "key", "radius", "nan"),
    ("spacing0", G, "key", "spacing", "0"),
    ("spacingneg", G, "key", "spacing", "-0.043"),
    ("spacing_overlap", G, "key", "spacing", "0.015"),
    ("maxp_small", G, "key", "maxParticles", "3"),
    ("maxp_frac", G, "key", "maxParticles", "10.5"),
    ("density0", G, "key", "density", "0"),
    ("densityneg", G, "key", "density", "-1600"),
    ("kn0", G, "key", "normalStiffness", "0"),
    ("knhuge", G, "key", "normalStiffness", "1e300"),
    ("cnneg", G, "key", "normalDamping", "-1"),
    ("ktneg", G, "key", "tangentialStiffness", "-1"),
    ("ctneg", G, "key", "tangentialDamping", "-6"),
    ("frictionneg", G, "key", "friction", "-0.8"),
    ("rollneg", G, "key", "rollingFriction", "-0.02"),
    ("cohneg", G, "key", "cohesionStiffness", "-5"),
    ("cohdistneg", G, "key", "cohesionMaxDistance", "-0.01"),
    ("substeps0", G, "key", "substeps", "0"),
    ("substepshuge", G, "key", "substeps", "5000"),
    ("model_bad", G, "key", "normalContactModel", "quadratic"),
    ("velocity_nan", G, "key", "velocity", "nan,0,0"),
    ("velocity_short", G, "key", "velocity", "1,0"),
    ("positions_radii_mismatch", G, "key", "positions", "0,0,0.1;0.1,0,0.1 radii=0.02,0.02,0.02"),
    ("positions_same", G, "key", "positions", "0,0,0.1;0,0,0.1"),
    ("positions_trailing", G, "key", "positions", "0,0,0.1;"),
    ("radii_ratio", G, "key", "positions", "0,0,0.1;0.5,0,0.1 radii=0.01,0.2"),
    ("needs_substeps", G, "key", "normalStiffness", "1e12"),
    ("quat0", G, "line", GRAN.replace(" 0.1 1 0 0 0 ", " 0.1 0 0 0 0 ")),
])  # a granular kind is free text (RaiSim reads none): `-` is no defect

# -- def: deformables (cloth over the ground)
DEF = ("deformable /World/Cloth cloth assets/cloth.obj 0 0 1 1 0 0 0 1 1 1 id=deformable_cloth parentGroupId=folder_world "
       "pinnedVertices=0,3 totalMass=0.2 distanceCompliance=1e-06 bendCompliance=1000 damping=0.01 "
       "collisionRadius=0.01 iterations=8 substeps=1 solverMode=xpbd material=mat_a")
D = "deformable /World/Cloth"
family("def", [DEF], [
    ("kind_bad", D, "pos", 2, "jelly"),
    ("mesh_missing", D, "pos", 3, "assets/nope.obj"),
    ("mesh_none", D, "pos", 3, "-"),
    ("mesh_junk", D, "pos", 3, "assets/junk.obj"),
    ("mesh_badidx", D, "pos", 3, "assets/badidx.obj"),
    ("mesh_nofaces", D, "pos", 3, "assets/nofaces.obj"),
    ("mesh_nanv", D, "pos", 3, "assets/nanv.obj"),
    ("mesh_dir", D, "pos", 3, "assets"),
    ("fem_open", D, "pos", 2, "fem"),
    ("mass0", D, "key", "totalMass", "0"),
    ("massneg", D, "key", "totalMass", "-0.2"),
    ("masshuge", D, "key", "totalMass", "1e20"),
    ("damping2", D, "key", "damping", "2"),
    ("dampingneg", D, "key", "damping", "-0.01"),
    ("iterationsneg", D, "key", "iterations", "-8"),
    ("substeps0", D, "key", "substeps", "0"),
    ("substepshuge", D, "key", "substeps", "100000000"),
    ("pin_oob", D, "key", "pinnedVertices", "0,99"),
    ("pin_neg", D, "key", "pinnedVertices", "0,-1"),
    ("pin_frac", D, "key", "pinnedVertices", "0,1.5"),
    ("pin_trailing", D, "key", "pinnedVertices", "0,"),
    ("poisson_half", D, "key", "poissonRatio", "0.6"),
    ("thickness0", D, "key", "youngsModulus", "1e6 thickness=0"),
    ("colrneg", D, "key", "collisionRadius", "-0.01"),
    ("colrhuge", D, "key", "collisionRadius", "100"),
    ("colrnan", D, "key", "collisionRadius", "nan"),
    ("solver_bad", D, "key", "solverMode", "magic"),
    ("scalehuge", D, "pos", 11, "1e13"),
    ("quat0", D, "line", DEF.replace(" 1 1 0 0 0 1 1 1 ", " 1 0 0 0 0 1 1 1 ")),
    ("poshuge", D, "pos", 4, "1e13"),
    ("scalekey0", D, "key", "scale", "0"),
])

# -- sens: sensors on a box
SB = box("/World/Box", "object_box", 0, 0, 0.2)
RGB = "sensor /World/Rgb rgb object_box 0 0 0.3 1 0 0 0 id=sensor_rgb width=32 height=24 verticalFov=60 nearPlane=0.05 farPlane=50 updateRate=30"
DEP = "sensor /World/Depth depth object_box 0 0 0.3 1 0 0 0 id=sensor_depth width=32 height=24 nearPlane=0.05 farPlane=50 outputPath=depth.png"
LID = ("sensor /World/Lidar lidar object_box 0 0 0.4 1 0 0 0 id=sensor_lidar lidarChannels=4 lidarSamples=16 "
       "lidarMinRange=0.1 lidarMaxRange=20 lidarVerticalFov=20 updateRate=10 outputPath=lidar")
IMU = "sensor /World/Imu imu object_box 0 0 0 1 0 0 0 id=sensor_imu updateRate=100 noiseStddev=0.01 noiseSeed=1 outputPath=imu.csv"
family("sens", [SB, RGB, DEP, LID, IMU], [
    ("rgb_w0", "/World/Rgb", "key", "width", "0"),
    ("rgb_whuge", "/World/Rgb", "key", "width", "20000"),
    ("rgb_wfrac", "/World/Rgb", "key", "width", "32.5"),
    ("rgb_fov180", "/World/Rgb", "key", "verticalFov", "180"),
    ("rgb_hfov0neg", "/World/Rgb", "key", "horizontalFov", "-10"),
    ("rgb_near0", "/World/Rgb", "key", "nearPlane", "0"),
    ("rgb_nearfar", "/World/Rgb", "key", "nearPlane", "60"),
    ("rgb_farhuge", "/World/Rgb", "key", "farPlane", "1e13"),
    ("rgb_cal_part", "/World/Rgb", "key", "calibrationFx", "30"),
    ("rgb_cal_fxneg", "/World/Rgb", "key", "calibrationFx", "-30 calibrationFy=30 calibrationCx=16 calibrationCy=12"),
    ("rgb_rate_neg", "/World/Rgb", "key", "updateRate", "-1"),
    ("rgb_rate_huge", "/World/Rgb", "key", "updateRate", "1e7"),
    ("rgb_parent_missing", "/World/Rgb", "pos", 3, "object_nope"),
    ("rgb_parent_camera", "/World/Rgb", "pos", 3, "camera_main"),
    ("rgb_parent_group", "/World/Rgb", "pos", 3, "folder_world"),
    ("rgb_quat0", "/World/Rgb", "line", RGB.replace(" 0.3 1 0 0 0 ", " 0.3 0 0 0 0 ")),
    ("rgb_posnan", "/World/Rgb", "pos", 4, "nan"),
    ("rgb_out_abs", "/World/Rgb", "key", "outputPath", "/tmp/rgb.png"),
    ("rgb_out_dotdot", "/World/Rgb", "key", "outputPath", "../rgb.png"),
    ("rgb_out_clash", "/World/Rgb", "key", "outputPath", "depth.png"),
    ("depth_noise_neg", "/World/Depth", "key", "noiseStddev", "-1"),
    ("depth_noise_huge", "/World/Depth", "key", "noiseMean", "1e13"),
    ("lidar_ch0", "/World/Lidar", "key", "lidarChannels", "0"),
    ("lidar_samples_neg", "/World/Lidar", "key", "lidarSamples", "-16"),
    ("lidar_rays_huge", "/World/Lidar", "key", "lidarSamples", "2000000"),
    ("lidar_range_inv", "/World/Lidar", "key", "lidarMinRange", "30"),
    ("lidar_range_huge", "/World/Lidar", "key", "lidarMaxRange", "1e13"),
    ("lidar_vfov_huge", "/World/Lidar", "key", "lidarVerticalFov", "200"),
    ("lidar_out_dot", "/World/Lidar", "key", "outputPath", "."),
    ("lidar_imu_inside", "/World/Imu", "key", "outputPath", "lidar/imu.csv"),
    ("imu_out_slash", "/World/Imu", "key", "outputPath", "imu/"),
    ("imu_out_abs", "/World/Imu", "key", "outputPath", "/tmp/imu.csv"),
    ("imu_noise_neg", "/World/Imu", "key", "noiseStddev", "-0.01"),
    ("imu_noise_nan", "/World/Imu", "key", "noiseStddev", "nan"),
    ("imu_parent_missing", "/World/Imu", "pos", 3, "object_nope"),
])

# -- vis: light, projected_decal, local_fog, reflection_probe,
#    irradiance_volume, point_cloud, instanced_visual
LIGHT = ("light /World/Spot 0 0 -1 2 id=light_spot parentGroupId=folder_world type=spot position=0,0,3 "
         "color=1,0.9,0.8 range=10 coneAngle=30 innerConeAngle=20 shadows=true shadowResolution=512")
DECAL = ("projected_decal /World/Decal 0 0 0 1 0 0 0 1 1 1 id=decal_a parentGroupId=folder_world "
         "halfExtents=0.5,0.5,0.2 color=1,1,1,1 edgeFade=0.05 albedoTexture=assets/tex.png albedoMix=1")
FOG = "local_fog /World/Fog 1 1 0.5 1 id=fog_a parentGroupId=folder_world color=0.5,0.6,0.7 density=0.5 edgeFade=0.3"
PROBE = "reflection_probe /World/Probe 0 0 1 3 id=probe_a parentGroupId=folder_world strength=1 boxProjection=false cubemapSize=32"
IVOL = ("irradiance_volume /World/Ivol 0 0 1 1 0 0 0 1 1 1 id=ivol_a parentGroupId=folder_world "
        "halfExtents=2,2,1 color=1,0.6,0.3,1 strength=0.6 edgeFade=0.3")
PC = "point_cloud /World/Cloud id=pointcloud_a parentGroupId=folder_world points=1,0,0;1.1,0,0;1.2,0,0 colors=1,0,0,1;0,1,0,1;0,0,1,1 pointSize=2"
IV = ("instanced_visual /World/Pebbles sphere id=instanced_a parentGroupId=folder_world size=0.05,0.05,0.05 "
      "colorA=0.4,0.4,0.4,1 colorB=0.6,0.6,0.6,1 instances=1,1,0,1,0,0,0,1,1,1;1.2,1,0,1,0,0,0,1,1,1 colorWeights=0.1,0.9")
family("vis", [LIGHT, DECAL, FOG, PROBE, IVOL, PC, IV], [
    ("light_type_bad", "/World/Spot", "key", "type", "laser"),
    ("light_color_short", "/World/Spot", "key", "color", "1,0.9"),
    ("light_intensity_nan", "/World/Spot", "pos", 5, "nan"),
    ("light_range_neg", "/World/Spot", "key", "range", "-10"),
    ("light_shadowres_frac", "/World/Spot", "key", "shadowResolution", "512.5"),
    ("light_position_word", "/World/Spot", "key", "position", "0,0,up"),
    ("light_area_neg", "/World/Spot", "key", "areaSize", "-1,1,0"),
    ("light_shadows_bad", "/World/Spot", "key", "shadows", "perhaps"),
    ("decal_quat0", "/World/Decal", "line", DECAL.replace(" 0 0 0 1 0 0 0 ", " 0 0 0 0 0 0 0 ")),
    ("decal_he_neg", "/World/Decal", "key", "halfExtents", "-0.5,0.5,0.2"),
    ("decal_fade_nan", "/World/Decal", "key", "edgeFade", "nan"),
    ("decal_tex_missing", "/World/Decal", "key", "albedoTexture", "assets/nope.png"),
    ("decal_color_short", "/World/Decal", "key", "color", "1,1"),
    ("decal_posinf", "/World/Decal", "pos", 2, "inf"),
    ("fog_rneg", "/World/Fog", "pos", 5, "-1"),
    ("fog_color_short", "/World/Fog", "key", "color", "0.5,0.6"),
    ("fog_center_nan", "/World/Fog", "pos", 2, "nan"),
    ("fog_density_word", "/World/Fog", "key", "density", "thick"),
    ("probe_rneg", "/World/Probe", "pos", 5, "-3"),
    ("probe_cube_frac", "/World/Probe", "key", "cubemapSize", "32.5"),
    ("probe_boxmin_short", "/World/Probe", "key", "boxMin", "-1,-1"),
    ("probe_strength_nan", "/World/Probe", "key", "strength", "nan"),
    ("ivol_he_neg", "/World/Ivol", "key", "halfExtents", "-2,2,1"),
    ("ivol_quat0", "/World/Ivol", "line", IVOL.replace(" 1 1 0 0 0 ", " 1 0 0 0 0 ")),
    ("ivol_color_short", "/World/Ivol", "key", "color", "1,0.6"),
    ("pc_colors_short", "/World/Cloud", "key", "colors", "1,0,0,1;0,1,0,1"),
    ("pc_points_trailing", "/World/Cloud", "key", "points", "1,0,0;1.1,0,0;1.2,0,0;"),
    ("pc_points_nan", "/World/Cloud", "key", "points", "1,0,0;nan,0,0;1.2,0,0"),
    ("iv_instances_short", "/World/Pebbles", "key", "instances", "1,1,0,1,0,0,0,1,1,1;1.2,1,0,1,0,0,0,1,1"),
    ("iv_weights_short", "/World/Pebbles", "key", "colorWeights", "0.1"),
    ("iv_mesh_missing", "/World/Pebbles", "line", IV.replace(" sphere ", " mesh ") + " meshPath=assets/nope.obj"),
    ("iv_mesh_junk", "/World/Pebbles", "line", IV.replace(" sphere ", " mesh ") + " meshPath=assets/junk.obj"),
    ("iv_prim_bad", "/World/Pebbles", "pos", 2, "blob"),
])

# -- wire: constraints between two boxes
WA = box("/World/A", "object_a", -0.5, 0, 1.5)
WB = box("/World/B", "object_b", 0.5, 0, 1.5)
WIRE = ("wire /World/Wire stiff object_a object_b 1 id=wire_ab localPositionA=0,0,0.2 localPositionB=0,0,0.2 "
        "stiffness=1000 damping=10 compliance=0 enabled=true")
W = "wire /World/Wire"
family("wire", [WA, WB, WIRE], [
    ("bodya_missing", W, "pos", 3, "object_nope"),
    ("length_neg", W, "pos", 5, "-1"),
    ("length_huge", W, "pos", 5, "1e13"),
    ("length_nan", W, "pos", 5, "nan"),
    ("kind_bad", W, "pos", 2, "rubber"),
    ("stiffness_neg", W, "key", "stiffness", "-1000"),
    ("damping_huge", W, "key", "damping", "1e16"),
    ("compliance_neg", W, "key", "compliance", "-1"),
    ("local_huge", W, "key", "localPositionA", "1e13,0,0"),
    ("local_short", W, "key", "localPositionA", "0,0"),
    ("enabled_bad", W, "key", "enabled", "sometimes"),
    ("fields_short", W, "line", "wire /World/Wire stiff object_a object_b id=wire_ab"),
])

# -- terrain: region, splat layer, foliage layer
H25 = ",".join(["0", "0.1", "0.2", "0.1", "0"] * 5)
W25 = ",".join(["0", "0.5", "1", "0.5", "0"] * 5)
TT = "terrain_texture 0 terrain_sand Sand color=0.76,0.68,0.5,1 albedo=- normal=- uvScale=4"
TT1 = "terrain_texture 1 terrain_rock Rock color=0.4,0.4,0.36,1 albedo=- normal=- uvScale=4"
TR = (f"terrain_region /World/Field 5 5 4 4 2 2 0 id=terrain_field parentGroupId=folder_world material=mat_a "
      f"baseTexture=0 visible=true collidable=true sourceKind=samples heights={H25}")
TS = f"terrain_splat_layer /World/Field slot=1 enabled=true strength=1 weights={W25}"
TF = ("terrain_foliage_layer /World/Field id=foliage_grass name=Grass enabled=true primitive=grass_blade "
      "size=0.03,0.03,0.15 colorA=0.3,0.55,0.2,1 colorB=0.45,0.65,0.25,1 densityPerSquareMeter=10 "
      "maxInstances=1000 minScale=0.7 maxScale=1.3 maxRenderedInstances=1000 seed=3")
T = "terrain_region /World/Field"
family("terrain", [TT, TT1, TR, TS, TF], [
    ("samples1", T, "pos", 2, "1"),
    ("samples_huge", T, "pos", 2, "20000"),
    ("samples_frac", T, "pos", 2, "5.5"),
    ("heights_short", T, "key", "heights", "0,0.1,0.2"),
    ("heights_nan", T, "key", "heights", H25.replace("0.2", "nan", 1)),
    ("heights_huge", T, "key", "heights", H25.replace("0.2", "1e13", 1)),
    ("heights_trailing", T, "key", "heights", H25 + ","),
    ("size0", T, "pos", 4, "0"),
    ("sizeneg", T, "pos", 5, "-4"),
    ("size_huge", T, "pos", 4, "1e13"),
    ("center_huge", T, "pos", 6, "1e13"),
    ("vcolors_short", T, "key", "vertexColors", "1,1,1,1;1,1,1,1"),
    ("holes_short", T, "key", "holes", "0,0,0"),
    ("texture_unknown", T, "key", "baseTexture", "7"),
    ("material_unknown", T, "key", "material", "mat_nope"),
    ("splat_weights_short", "terrain_splat_layer", "key", "weights", "0,1"),
    ("splat_terrain_unknown", "terrain_splat_layer", "pos", 1, "/World/Nope"),
    ("splat_slot_unknown", "terrain_splat_layer", "key", "slot", "9"),
    ("foliage_density_short", "terrain_foliage_layer", "key", "density", "1,1,1"),
    ("foliage_maxinst_huge", "terrain_foliage_layer", "key", "maxInstances", "99999999999999"),
    ("foliage_mesh_missing", "terrain_foliage_layer", "key", "primitive", "mesh", "meshPath", "assets/nope.obj"),
    ("foliage_mesh_junk", "terrain_foliage_layer", "key", "primitive", "mesh", "meshPath", "assets/junk.obj"),
    ("foliage_dens_huge", "terrain_foliage_layer", "key", "densityPerSquareMeter", "1e7", "maxInstances", "100000000",
     "maxRenderedInstances", "100000000"),
    ("foliage_terrain_unknown", "terrain_foliage_layer", "pos", 1, "/World/Nope"),
    ("foliage_size_short", "terrain_foliage_layer", "key", "size", "0.03,0.03"),
    ("layer_before_region", "terrain_splat_layer", "move", "terrain_region"),
])

# -- cam: camera records and their outputPath
C = "camera /World/Cam"
CAM2 = "camera /World/Cam2 4 0 2 0 0.2588190 0 0.9659258 50 0.05 50 64 48 rgb true id=camera_two parentGroupId=folder_world outputPath=two.png"
family("cam", [box("/World/Box", "object_box", 0, 0, 0.2), CAM2], [
    ("out_abs", C, "key", "outputPath", "/tmp/cam.png"),
    ("out_dotdot", C, "key", "outputPath", "../cam.png"),
    ("out_dotdot_mid", C, "key", "outputPath", "a/../../cam.png"),
    ("out_jpg", C, "key", "outputPath", "cam.jpg"),
    ("out_npy", C, "key", "outputPath", "cam.npy"),
    ("out_dir", C, "key", "outputPath", "cam.png/"),
    ("out_nul", C, "key", "outputPath", "cam.png%00x"),
    ("out_pct_bad", C, "key", "outputPath", "cam%ZZ.png"),
        ("whuge", C, "pos", 12, "20000"),
    ("wneg", C, "pos", 12, "-64"),
    ("near0", C, "pos", 10, "0"),
    ("nearfar", C, "pos", 10, "60"),
    ("fov_nan", C, "pos", 9, "nan"),
    ("quat0", C, "line", HEADER[6].replace("0.9659258 0 0.2588190 0", "0 0 0 0")),
    ("ortho0", C, "key", "projection", "orthographic orthoScale=0"),
    ("ortho_huge", C, "key", "projection", "orthographic orthoScale=1e13"),
    ("projection_bad", C, "key", "projection", "fisheye"),
    ("enabled_bad", C, "pos", 15, "sometimes"),
    ("parent_unknown", C, "key", "parentGroupId", "folder_nope"),
])

# -- urdf: a floating-base arm from a URDF written here
RES_U = "articulated_resource arm_res Arm assets/arm.urdf"
ART_U = ("articulated /World/Arm arm_res 0 0 1 1 0 0 0 true true id=articulated_arm parentGroupId=folder_world "
         "generalizedCoordinate=0,0,1,1,0,0,0,0.1,-0.1 generalizedVelocity=0,0,0,0,0,0,0,0")
IK_U = "articulated_ik /World/Arm lower 0.1,0,1.5 enabled=true maxIterations=50"
A = "articulated /World/Arm"


def u(name, **kw):
    """A defect in the URDF file: the resource names assets/robots/NAME.urdf."""
    return (name, "articulated_resource", "pos", 3, f"assets/robots/{name}.urdf",
            {f"assets/robots/{name}.urdf": urdf(**kw)})


def ufile(name, text):
    return (name, "articulated_resource", "pos", 3, f"assets/robots/{name}.urdf",
            {f"assets/robots/{name}.urdf": text})


family("urdf", [RES_U, ART_U, IK_U, box("/World/Box", "object_box", 2, 0, 0.2)], [
    ("file_missing", "articulated_resource", "pos", 3, "assets/robots/nope.urdf"),
    ufile("u_not_xml", "this is not xml <robot\n"),
    ufile("u_empty", ""),
    ufile("u_not_robot", '<?xml version="1.0"?>\n<mujoco_not/>\n'),
    u("u_massneg", base_mass="-2"),
    u("u_masshuge", base_mass="1e20"),
    u("u_massnan", base_mass="nan"),
    u("u_inertianeg", base_inertia="-0.02"),
    u("u_inertiahuge", base_inertia="1e25"),
    u("u_jtype_bad", j1_type="wobbly"),
    u("u_floating_joint", j1_type="floating"),
    u("u_axis0", j1_axis="0 0 0"),
    u("u_axisnan", j1_axis="nan 1 0"),
    u("u_parent_missing", j1_parent="nowhere"),
    u("u_two_roots", j2_child="orphan_child", extra='  <link name="orphan_child"/>\n'),
    u("u_cycle", extra='  <joint name="j3" type="fixed"><parent link="lower"/><child link="base"/></joint>\n'),
    u("u_dup_link", extra='  <link name="lower"/>\n'),
    u("u_origin_huge", j2_origin="0 0 1e13"),
    u("u_box_huge", upper_geom='<box size="1e13 0.1 0.3"/>'),
    u("u_colmesh_missing", lower_col='<mesh filename="nope.obj"/>'),
    u("u_limit_nan", limit='lower="nan" upper="1"'),
    ("gc_short", A, "key", "generalizedCoordinate", "0,0,1,1,0,0,0,0.1"),
    ("gc_long", A, "key", "generalizedCoordinate", "0,0,1,1,0,0,0,0.1,-0.1,0"),
    ("gc_nan", A, "key", "generalizedCoordinate", "0,0,1,1,0,0,0,nan,-0.1"),
    ("gc_huge", A, "key", "generalizedCoordinate", "0,0,1,1,0,0,0,1e13,-0.1"),
    ("gc_quat0", A, "key", "generalizedCoordinate", "0,0,1,0,0,0,0,0.1,-0.1"),
    ("gc_trailing", A, "key", "generalizedCoordinate", "0,0,1,1,0,0,0,0.1,-0.1,"),
    ("gv_short", A, "key", "generalizedVelocity", "0,0,0,0,0,0,0"),
    ("jointorder_unknown", A, "key", "jointOrder", "j1;j9"),
    ("jointorder_repeat", A, "key", "jointOrder", "j1;j1"),
    ("resource_unknown", A, "pos", 2, "nope_res"),
    ("quat0", A, "line", ART_U.replace(" 1 1 0 0 0 true", " 1 0 0 0 0 true")),
    ("module_missing", "articulated_resource", "key", "modules", "nope_module"),
    ("ik_frame_unknown", "articulated_ik", "pos", 2, "hand"),
    ("ik_iter_neg", "articulated_ik", "key", "maxIterations", "-5"),
    ("ik_method_bad", "articulated_ik", "key", "inverseMethod", "guess"),
    ("ik_orphan", None, "add", "articulated_ik /World/Nope lower 0.1,0,1.5"),
    ("sensor_link_unknown", None, "add",
     "sensor /World/ArmCam rgb articulated_arm 0 0 0.1 1 0 0 0 id=sensor_armcam parentLink=finger width=32 height=24"),
    ("wire_index_oob", None, "add",
     "wire /World/Tether stiff articulated_arm object_box 1 id=wire_tether localIndexA=7"),
])

# -- mjcf: a fixed-base arm from an MJCF file written here
RES_M = "articulated_resource mj_res ArmM assets/arm.xml"
ART_M = ("articulated /World/ArmM mj_res 0 0 0 1 0 0 0 true true id=articulated_armm parentGroupId=folder_world "
         "generalizedCoordinate=0.1,-0.1 generalizedVelocity=0,0")
M = "articulated /World/ArmM"


def m(name, **kw):
    return (name, "articulated_resource", "pos", 3, f"assets/robots/{name}.xml",
            {f"assets/robots/{name}.xml": mjcf(**kw)})


def mfile(name, text):
    return (name, "articulated_resource", "pos", 3, f"assets/robots/{name}.xml",
            {f"assets/robots/{name}.xml": text})


family("mjcf", [RES_M, ART_M], [
    mfile("m_not_xml", "<mujoco model='x'><worldbody>\n"),
    m("m_unknown_attr", body1_extra=' colour="red"'),
    m("m_unknown_elem", inner='        <gizmo/>\n'),
    m("m_mass_neg", geom2='<geom name="g2" type="capsule" fromto="0 0 0 0 0 0.3" size="0.04" mass="-1"/>'),
    m("m_size_huge", geom2='<geom name="g2" type="sphere" size="1e13"/>'),
    m("m_joint_bad", joint1='<joint name="h1" type="wobbly" axis="0 1 0"/>'),
    m("m_joint_axis0", joint1='<joint name="h1" type="hinge" axis="0 0 0"/>'),
    m("m_inner_free", inner='        <body name="link3" pos="0 0 0.3"><freejoint/><geom type="sphere" size="0.03"/></body>\n'),
    m("m_composite", inner='        <composite type="grid" count="3 3 1" spacing="0.05"><geom size="0.01"/></composite>\n'),
    m("m_include_missing", tail='  <include file="nope.xml"/>\n'),
    m("m_dup_body", inner='        <body name="link1"><geom type="sphere" size="0.03"/></body>\n'),
    m("m_numeric_bad", body1_extra=' pos="0 0 x"'),
    ("gc_short", M, "key", "generalizedCoordinate", "0.1"),
    ("gc_long", M, "key", "generalizedCoordinate", "0.1,-0.1,0"),
    ("gv_long", M, "key", "generalizedVelocity", "0,0,0"),
    ("gc_huge", M, "key", "generalizedCoordinate", "1e13,-0.1"),
    ("jointorder_unknown", M, "key", "jointOrder", "h1;hx"),
])


# ---------------------------------------------------------------- apply
def set_key(line, k, v):
    toks = line.split(" ")
    for i, t in enumerate(toks):
        if k and t.startswith(k + "="):
            toks[i] = f"{k}={v}"
            return " ".join(toks)
    return line + f" {k}={v}"


def apply(lines, d):
    name, target, op, *args = d
    files = {}
    if args and isinstance(args[-1], dict):
        files = args.pop()
    lines = list(lines)
    idx = None
    if target is not None:
        hits = [i for i, l in enumerate(lines) if target in l]
        if not hits:
            raise SystemExit(f"{name}: no base line contains {target!r}")
        idx = hits[0]
    if op == "key":
        for k, v in zip(args[0::2], args[1::2]):
            lines[idx] = set_key(lines[idx], k, v)
    elif op == "pos":
        toks = lines[idx].split(" ")
        toks[args[0]] = args[1]
        lines[idx] = " ".join(toks)
    elif op == "line":
        lines[idx] = args[0]
    elif op == "add":
        lines.append(args[0])
        idx = len(lines) - 1
    elif op == "move":
        moved = lines.pop(idx)
        idx = next(i for i, l in enumerate(lines) if args[0] in l)
        lines.insert(idx, moved)
    else:
        raise SystemExit(f"{name}: unknown op {op}")
    return lines, idx + 1, files, f"{op} {' '.join(str(a) for a in args)}".strip()


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    if isinstance(data, str):
        data = data.encode("utf-8", "surrogateescape")
    with open(path, "wb") as f:
        f.write(data)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: gen-catalogue.py OUTDIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, text in ASSETS.items():
        write(os.path.join(out, "assets", name), png_1x1() if text is None else text)
    write(os.path.join(out, "assets", "arm.urdf"), urdf())
    write(os.path.join(out, "assets", "arm.xml"), mjcf())
    manifest = ["# name\tline\tfamily\tdefect"]
    seen = set()
    for fam, (base, defects) in FAMILIES.items():
        scenes = [(f"{fam}_ok", base, 0, {}, "control: the valid base")]
        for d in defects:
            lines, line, files, desc = apply(base, d)
            scenes.append((f"{fam}_{d[0]}", lines, line, files, desc))
        for name, lines, line, files, desc in scenes:
            if name in seen:
                raise SystemExit(f"duplicate scene name {name}")
            seen.add(name)
            write(os.path.join(out, name + ".rscene"), "\n".join(lines) + "\n")
            for rel, text in files.items():
                write(os.path.join(out, rel), text)
            safe = desc.replace("\t", " ").encode("ascii", "backslashreplace").decode()
            safe = "".join(c if c.isprintable() else f"\\x{ord(c):02x}" for c in safe)
            manifest.append(f"{name}\t{line}\t{fam}\t{safe}")
    write(os.path.join(out, "manifest.tsv"), "\n".join(manifest) + "\n")
    print(f"{len(manifest) - 1} scenes ({len(FAMILIES)} controls) in {out}")


if __name__ == "__main__":
    main()
