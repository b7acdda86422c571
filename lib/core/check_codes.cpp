// The registry of every diagnostic code any tool emits: the code, its
// severity, the layer that checks it, the tools that report it and one line
// of explanation.  --list-checks, the man pages and the tests read this one
// table; tests/scene/code_registry_test.cpp fails when lib/ or cmd/ emits a
// code that is not here, or when README.md or a man page quotes one that
// does not exist.
#include <algorithm>

#include "core/check.hpp"

namespace rscene {
namespace {

constexpr Severity E = Severity::Error;
constexpr Severity W = Severity::Warning;
constexpr CheckLayer Core = CheckLayer::Core, Scene = CheckLayer::Scene, Sim = CheckLayer::Sim,
                     Json = CheckLayer::Json, Render = CheckLayer::Render, Robot = CheckLayer::Robot,
                     Xml = CheckLayer::Xml;
// Who reports a code: the validator alone, or also sim and render, whose
// scene model (lib/scene/reader.cpp) reads values with the validator's codes.
// The loader's codes (RS1001-RS1010) stop every tool that reads a scene.
constexpr std::string_view V = "validate", VSR = "validate sim render", All = "every tool";

constexpr CheckInfo kChecks[] = {
    // RS1xxx syntax (RS1001..RS1010 come from the loader)
    {"RS1001", E, Core, All, "missing raisim_engine_scene header"},
    {"RS1002", E, Core, All, "unsupported rscene version (only 1 and 2 exist)"},
    {"RS1003", E, Core, All, "invalid percent escape"},
    {"RS1004", E, Core, All, "scene text contains a NUL byte"},
    {"RS1005", E, Core, All, "invalid UTF-8"},
    {"RS1006", E, Core, All, "control character in a token"},
    {"RS1007", E, Core, All, "wrong number of positional fields for the record kind"},
    {"RS1008", E, Core, All, "positional field after key=value fields"},
    {"RS1009", E, Core, All, "key=value token without a key"},
    {"RS1010", E, Core, All, "input too large"},
    {"RS1101", W, Core, V, "key repeated in one record (the last one wins)"},
    // RS2xxx types
    {"RS2001", E, Core, VSR, "value is not a number"},
    {"RS2002", E, Core, VSR, "number is not finite (nan, inf or out of range)"},
    {"RS2003", E, Core, VSR, "value is not an integer in range"},
    {"RS2004", E, Core, VSR, "collision group or mask is not an unsigned 64-bit integer"},
    {"RS2005", E, Core, VSR, "value is not a flag (true/false, 1/0, yes/no, on/off)"},
    {"RS2006", E, Core, VSR, "unknown name for a closed enumeration"},
    {"RS2007", W, Core, VSR, "name not known for an open enumeration (newer writers may add names; sim and render say so of a sensor kind, which they neither render nor simulate)"},
    {"RS2008", E, Core, VSR, "vector, quaternion or color with the wrong number of components"},
    {"RS2009", E, Core, VSR, "number list with an empty entry or a trailing separator"},
    // RS3xxx names and references
    {"RS3001", W, Core, V, "unknown record tag (kept and ignored)"},
    {"RS3002", W, Core, V, "unknown key (kept and ignored)"},
    {"RS3003", E, Core, V, "duplicate node path"},
    {"RS3004", E, Core, V, "duplicate id (explicit or default)"},
    {"RS3005", W, Core, V, "node path not rooted at /World"},
    {"RS3006", E, Core, V, "parent (parentGroupId or parentId) names no node"},
    {"RS3007", W, Core, V, "node parented to a non-group node inherits its transform"},
    {"RS3008", E, Core, V, "material names no material record"},
    {"RS3009", W, Core, V, "contact material named by no contact_material record"},
    {"RS3010", E, Core, V, "articulated resource names no articulated_resource record"},
    {"RS3011", E, Core, V, "terrain texture slot names no terrain_texture record"},
    {"RS3012", E, Core, VSR, "body reference names no node"},
    {"RS3013", E, Core, VSR, "terrain reference names no terrain_region"},
    {"RS3014", E, Core, VSR, "node reference names no node of the right kind"},
    {"RS3015", E, Core, V, "child record with no parent record before it"},
    {"RS3016", W, Core, V, "repeated singleton record replaces the earlier one"},
    {"RS3017", E, Core, VSR, "parent chain forms a cycle"},
    // RS4xxx sizes and values
    {"RS4001", E, Core, VSR, "terrain sample count per axis outside 2..16384"},
    {"RS4002", E, Core, VSR, "terrain has more than 64 Mi samples"},
    {"RS4003", E, Core, VSR, "per-sample list length differs from the terrain's sample count"},
    {"RS4004", E, Core, VSR, "instance list length is not a multiple of 10"},
    {"RS4005", E, Core, V, "colorWeights count differs from the instance count"},
    {"RS4006", E, Core, VSR, "vertexColors count differs from the terrain's sample count"},
    {"RS4007", E, Core, V, "generalizedCoordinate and generalizedVelocity lengths disagree"},
    {"RS4008", E, Scene, VSR, "dynamic object or compound without positive mass (ground and half_space are static)"},
    {"RS4009", E, Core, VSR, "zero quaternion (length below 1e-12)"},
    {"RS4010", W, Core, V, "quaternion not of unit length (off by more than 1e-3)"},
    {"RS4011", E, Core, V, "negative size, radius or length"},
    {"RS4012", E, Core, VSR, "camera or sensor near plane not positive or not below the far plane (sim and render: sensors)"},
    {"RS4013", W, Core, V, "field of view outside the range it is clamped to"},
    {"RS4014", E, Core, VSR, "terrain size not positive"},
    // RS5xxx files (--check-files)
    {"RS5001", E, Core, "validate sim render", "asset file does not exist or is not a regular file (validate --check-files; sim for collision meshes; render for meshes and textures)"},
    // RS6xxx what RaiSim 2.7.1 refuses (--profile raisim)
    {"RS6001", E, Core, V, "record kind RaiSim does not load"},
    {"RS6002", E, Core, V, "key repeated in one record"},
    {"RS6003", E, Core, V, "version-1 asset_root other than . or an absolute path"},
    {"RS6004", E, Core, V, "node parented to a non-group node while transforms are inherited"},
    {"RS6005", E, Core, V, "terrain not sampled, hidden or not collidable"},
    {"RS6006", E, Core, V, "terrain layer before its terrain"},
    {"RS6007", E, Core, V, "enabled instanced visual that is a grass patch or a ground"},
    {"RS6008", E, Core, V, "enabled wire with a negative length or body index"},
    {"RS6009", E, Core, V, "name not known to RaiSim"},
    // RS7xxx the scene model (lib/scene) and the simulator
    {"RS7001", E, Scene, VSR, "point cloud colors that are not one per point"},
    {"RS7003", E, Scene, VSR, "body shape with a zero or negative physical size"},
    {"RS7004", E, Scene, VSR, "mesh body without a mesh path"},
    {"RS7007", E, Scene, VSR, "mesh file that cannot be read or has no triangles (a body's collision mesh, a compound child's; a foliage mesh for validate and render); validate with --check-files"},
    {"RS7008", E, Scene, VSR, "time_step not positive"},
    {"RS7009", E, Scene, VSR, "compound child that is a plane (ground or half_space)"},
    {"RS7010", W, Sim, "sim", "records kept but not simulated (sensor records of kinds rscene-sim does not model)"},
    {"RS7011", W, Scene, VSR, "wire to a node the simulator does not model, skipped"},
    {"RS7012", W, Sim, "sim", "dynamic body left the world (fell far below the static geometry or out of the broadphase bounds); no longer simulated"},
    {"RS7020", E, Scene, VSR, "dynamic mass below the smallest normal double or above 1e15 kg (Bullet would take it for immovable)"},
    {"RS7021", E, Scene, VSR, "body pose that is not finite or more than 1e12 m from its frame's origin, or an orientation that does not normalise to a unit quaternion"},
    {"RS7022", E, Scene, VSR, "time_step that is not finite or outside 1e-9 to 1 s"},
    {"RS7023", E, Sim, "sim", "run longer than --max-steps"},
    {"RS7024", E, Sim, "sim", "a body's state stopped being finite, or a robot's diverged (a joint at 1e6 rad/s), while stepping (nothing is written)"},
    {"RS7025", E, Sim, "sim", "more overlapping body pairs than --max-pairs"},
    {"RS7026", E, Scene, VSR, "size, scale, wire attachment or length, terrain size, centre or height, or gravity larger than 1e12 in magnitude (m, m/s^2)"},
    {"RS7027", E, Scene, VSR, "wire stiffness, damping or compliance, friction or restitution negative or above 1e15; solver iterations outside 0..10000"},
    {"RS7028", E, Scene, VSR, "camera width or height outside 0..16384"},
    // RS703x reading robot files (lib/robot/load.hpp); RS704x an articulated
    // record against its model (lib/robot/instance.hpp).
    {"RS7030", E, Robot, VSR, "robot file (URDF or MJCF) that does not parse or that MuJoCo's compiler refuses"},
    {"RS7031", W, Robot, VSR, "robot file element that cannot be used, skipped (xacro leftovers, unknown geometry ...)"},
    {"RS7032", E, Robot, VSR, "robot model that is not a tree (no root, two roots, a joint to an unknown link, a cycle)"},
    {"RS7033", E, Robot, VSR, "module (a URDF fragment) not found in RaiSim's search order"},
    {"RS7034", E, Robot, VSR, "articulated record with no robot file to load"},
    {"RS7035", E, Robot, VSR, "robot model number no simulator can stand behind: mass outside 0..1e15 kg, inertia not finite, negative or beyond 1e21, length beyond 1e12 m, joint coefficient outside 0..1e15"},
    {"RS7036", E, Robot, VSR, "model from MJCF that the robot model cannot hold (a free joint below the top level or beside other joints, a second top-level body beside a floating base, a <composite>)"},
    {"RS7037", W, Robot, VSR, "element of an MJCF file converted approximately (an ellipsoid geom as a sphere), or a warning of MuJoCo's compiler"},
    {"RS7040", E, Robot, VSR, "generalizedCoordinate length differs from the model's"},
    {"RS7041", E, Robot, VSR, "generalizedVelocity length differs from the model's"},
    {"RS7042", E, Robot, VSR, "jointOrder names an unknown, fixed or repeated joint, or leaves one out"},
    {"RS7043", W, Robot, VSR, "quaternion in generalizedCoordinate not of unit length (normalised), or zero (error)"},
    {"RS7044", E, Robot, "validate sim", "articulated_ik frame that is no joint or link of the robot (a warning when the target is disabled)"},
    {"RS7045", E, Robot, VSR, "sensor parentLink that is no link of the articulated system its parentObject names"},
    {"RS7046", E, Robot, "validate sim", "wire localIndexA/B past the body count of the articulated system it names (movable bodies, base included)"},
    {"RS7047", W, Robot, "sim", "articulated_ik target not reached within its tolerances (the message names the residual)"},
    {"RS7048", E, Robot, "validate sim", "articulated_ik setting that cannot be used (iterations, tolerances, gains, unknown inverseMethod)"},
    {"RS7049", E, Robot, VSR, "generalizedCoordinate or generalizedVelocity entry beyond 1e12 in magnitude"},
    // RS705x simulating robots (lib/sim)
    {"RS7051", W, Sim, "sim", "convexifyCollisionMeshes=false: robot mesh collisions are simulated as convex hulls all the same"},
    {"RS7052", E, Robot, VSR, "robot with more than 1000 bodies (movable joints + 1): Bullet's cost grows with their square"},
    // RS706x sensors: sensor sets of robot files (lib/robot/sensor_set.hpp),
    // sensor records and output paths (lib/scene/sensor_check.hpp).
    {"RS7060", E, Robot, VSR, "sensor set file that a URDF link names (sensor=) not found in RaiSim's search order"},
    {"RS7061", E, Robot, VSR, "sensor set file that does not parse: not well-formed XML, root not <sensor_set>, a sensor without a name or type, a value that is not a number (or a whole number where one is needed), an origin beyond 1e12 m"},
    {"RS7062", W, Robot, VSR, "sensor set element that cannot be used, skipped (unknown sensor type, repeated sensor name, noise other than gaussian read as gaussian, an empty sensor attribute)"},
    {"RS7063", E, Scene, VSR, "sensor parentObject that names a node that is no body (a camera, group, light, sensor ...): only an object, a compound or an articulated system carries a sensor"},
    {"RS7064", E, Scene, VSR, "camera-like sensor image width or height outside 1..16384 or field of view outside (0, 180) degrees; sensor far plane beyond 1e12 m"},
    {"RS7065", E, Scene, VSR, "sensor calibration given in part (fx, fy, cx, cy: all four or none), or fx or fy not positive"},
    {"RS7066", E, Scene, VSR, "lidar channels or samples below 1 or more than 4194304 rays a scan, ranges not 0 <= min < max <= 1e12 m, vertical field of view outside 0..180 degrees"},
    {"RS7067", E, Scene, VSR, "sensor updateRate outside 0..1e6 Hz, noise standard deviation negative, noise or IMU limit beyond 1e12"},
    {"RS7068", W, Scene, VSR, "sensor parentLink whose parentObject is not an articulated system (the link is not used)"},
    {"RS7069", E, Scene, VSR, "sensor or camera outputPath that is absolute, names a drive, has a '..' part or a NUL byte (tools write only inside their output folder); a camera's or camera-like sensor's image path that names a folder or another format than PNG (.jpg, .npy ...); a LiDAR or IMU outputPath that names the --sensors folder itself ('.'), an IMU outputPath ending in '/'"},
    // RS707x recording sensors (lib/sim/sensor_recorder.hpp, rscene-sim --sensors)
    {"RS7070", E, Scene, VSR, "two sensors that would write one output: two enabled sensor records with the same outputPath; two LiDARs or IMUs (records or robots' sensor sets) whose rscene-sim --sensors outputs are one place or one inside the other (an IMU file in a LiDAR's folder)"},
    {"RS7071", W, Sim, "sim", "physical sensor kind rscene-sim does not record (force_torque, unknown kinds), skipped"},
    {"RS7072", W, Scene, VSR, "lidar lidarVerticalFov of 0 with more than one channel (every ring scans the same plane)"},
    {"RS7073", W, Scene, VSR, "sensor segmentation=true on a kind that draws no image (lidar, imu, force_torque): not used"},
    {"RS7074", E, Scene, VSR, "camera orthoScale not finite and positive (at most 1e12) under an orthographic projection"},
    // RS708x deformable and granular records (lib/scene: granular.hpp, deformable_check.hpp,
    // deformable_model.hpp; validate, sim and render judge them alike, a deformable's mesh with --check-files)
    {"RS7080", E, Scene, VSR, "deformable mesh that is not a usable OBJ surface (unreadable, not OBJ, a face index past its vertices, no triangles); validate with --check-files"},
    {"RS7081", E, Scene, VSR, "deformable record that cannot be simulated (a kind other than cloth, mass_spring or fem, a value out of range; with its mesh (validate: --check-files): a pinned vertex that is not one of the mesh's, an open mesh to fill, a collisionRadius larger than the body)"},
    {"RS7082", E, Scene, VSR, "granular record whose grains cannot be made (more particles than maxParticles or 2,000,000, radii that do not match positions, a box fill with a radius or spacing that is not positive)"},
    {"RS7086", W, Scene, VSR, "granular substeps raised for stability (the time step is past 0.6 of the critical step of the contact law for the lightest grain); the message says what it costs"},
    {"RS7087", E, Scene, VSR, "granular record whose stability needs more than 1000 substeps per world step (lower normalStiffness or normalDamping, raise radius or density, or shorten time_step)"},
    {"RS7088", E, Scene, VSR, "granular value out of range (a radius, density or stiffness that is not positive and finite, a negative damping, friction or cohesion, radii spanning more than a factor of 10, substeps outside 1 to 1000)"},
    {"RS7089", E, Scene, VSR, "granular particles that start overlapping by more than half their radii (a box fill with spacing below the radius, positions written at one point)"},
    // RS709x the scene model's bodies, continued (scene/limits.hpp)
    {"RS7090", E, Scene, VSR, "custom inertia diagonal (customInertia=true on a dynamic object, inertiaDiagonal of a dynamic compound) not positive and finite or above 1e15 kg m^2"},
    // RS8xxx JSON input (rscene-from-json)
    {"RS8001", E, Json, "from-json", "invalid JSON"},
    {"RS8002", E, Json, "from-json", "valid JSON that is not a scene: wrong type, missing or unknown field"},
    // RS81xx RaiSim world XML: RS8101-8109 reading and expanding (rscene-from-xml),
    // RS8110-8129 mapping elements to records, RS8130-8139 export (rscene-to-xml)
    {"RS8101", E, Xml, "from-xml", "world XML that cannot be read: not well-formed, not a <raisim> document, or past a size limit"},
    {"RS8102", E, Xml, "from-xml", "world XML that declares entities (a DOCTYPE internal subset) or uses an &name; other than XML's five"},
    {"RS8103", E, Xml, "from-xml", "include that cannot be followed: no file attribute, unreadable, a cycle, nested too deep, or out of place"},
    {"RS8104", E, Xml, "from-xml", "parameter error: @@NAME used but set nowhere, defined from itself, a <params> entry without value"},
    {"RS8105", E, Xml, "from-xml", "{...} expression that cannot be evaluated: syntax, unknown function, division by zero, log of a non-positive number, non-finite result, too long or deep"},
    {"RS8106", E, Xml, "from-xml", "array without idx, start, end or increment, with bounds that are not integers, or whose increment never reaches end"},
    {"RS8107", E, Xml, "from-xml", "template expansion past a limit: elements, loop iterations, nesting depth, bytes of values or of files read"},
    {"RS8108", E, Xml, "from-xml", "exist value other than true, false, 1 or 0"},
    {"RS8109", E, Xml, "from-xml", "object_class that cannot be used: no type, defined twice, a built-in name, a wrong object_param, an unknown compound child"},
    {"RS8110", E, Xml, "from-xml", "element or attribute whose value cannot become a record field"},
    {"RS8111", W, Xml, "from-xml", "element or attribute with no .rscene field (unknown, or not modelled), not converted"},
    {"RS8112", E, Xml, "from-xml", "element without a required child or attribute (a sphere's radius, a mesh's file_name ...)"},
    {"RS8113", W, Xml, "from-xml", "converted approximately: a repeated name renamed, a procedural heightmap left flat, a robot file not read, a mesh file not found"},
    {"RS8114", E, Xml, "from-xml", "heightmap PNG or text file that cannot be read"},
    {"RS8125", E, Xml, "from-xml", "converted record that rscene-validate, rscene-sim or rscene-to-xml would refuse (their code in the message), at the element that made it"},
    {"RS8130", E, Xml, "to-xml", "scene that cannot be written as a world XML"},
    {"RS8131", W, Xml, "to-xml", "articulated system whose robot file cannot be read: exported with its urdf_path and the state as written"},
    // RS9xxx rendering (rscene-render)
    {"RS9001", E, Render, "render", "mesh file that cannot be read (a warning with --allow-missing-assets)"},
    {"RS9002", W, Render, "render", "texture not drawn"},
    {"RS9003", W, Render, "render", "background image (HDR) missing; the sky is drawn instead"},
    {"RS9004", W, Render, "render", "more lights than the GL light buffer holds (thousands); the rest are not drawn"},
    {"RS9010", E, Render, "render", "shader build failed"},
    {"RS9011", E, Render, "render", "cannot create the framebuffer"},
    {"RS9012", E, Render, "render", "an OpenGL call failed"},
    {"RS9013", E, Render, "render", "camera image larger than --max-pixels or 16384 on a side"},
    {"RS9014", E, Render, "render", "more instances to draw than --max-instances"},
    // RS903x robots in rendering
    {"RS9030", W, Render, "render", "articulated system whose model has no visual elements: nothing is drawn"},
    // RS904x render passes and views (rgb, depth, segmentation)
    {"RS9040", E, Render, "render", "view that cannot be drawn: image size, intrinsics or near/far planes out of range"},
    // RS904x views, output names and trajectories (rscene-render --all-cameras, --trajectory)
    {"RS9045", W, Render, "render", "camera renderMode rscene-render does not draw as written: the color image is drawn"},
    {"RS9046", E, Render, "render", "malformed --trajectory line (not what rscene-sim --trajectory writes)"},
    {"RS9047", E, Render, "render", "--trajectory names a body, robot or joint the scene does not have"},
    {"RS9048", E, Render, "render", "outputPath a scene may not write to (absolute, or with '..'), or two views writing one file"},
    // RS905x lights and shadows (RS9050..)
    {"RS9050", W, Render, "render", "more than 64 lights cast shadows (the strongest do), or shadow maps reduced to fit the shadow atlas"},
    // RS9055 and on: projected decals, fog, irradiance volumes
    {"RS9055", W, Render, "render", "more than 1024 decals, fog spheres or irradiance volumes of one kind in view (the nearest are drawn), or decal textures past what this OpenGL holds"},
    // RS906x reflections: environment light and reflection probes
    {"RS9060", W, Render, "render", "reflection probes not drawn: the OpenGL has no cube map arrays"},
    {"RS9061", W, Render, "render", "more than 8 reflection probes; the rest are not drawn"},
    // RS907x geometry records drawn: foliage, wires, deformables, granular media
    {"RS9070", E, Render, "render", "granular record with more particles than the --max-instances left (its own maxParticles is RS7082)"},
    {"RS9072", W, Render, "render", "terrain_foliage_layer primitive rscene-render does not draw: drawn as grass_blade"},
};

}  // namespace

std::span<const CheckInfo> checkTable() { return kChecks; }

const CheckInfo* checkInfo(std::string_view code) {
  auto it = std::find_if(std::begin(kChecks), std::end(kChecks), [&](const CheckInfo& c) { return c.code == code; });
  return it == std::end(kChecks) ? nullptr : it;
}

}  // namespace rscene
