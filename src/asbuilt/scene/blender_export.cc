#include "asbuilt/scene/blender_export.h"

#include <fmt/format.h>

#include "asbuilt/scene/scene_json.h"
#include "asbuilt/util/error.h"
#include "asbuilt/util/file.h"

namespace asbuilt {
namespace {

// The builder: reads SCENE / MATERIALS / VIEWS / SETTINGS (set above it) and
// makes the Blender scene. Written against the 3.4 API and kept to calls
// that 4.x still has (node inputs looked up by name with fallbacks).
constexpr const char* kBuilder = R"PY(
import math
import os

import bpy
from mathutils import Vector

LABEL_OTHER, LABEL_WALL, LABEL_DOOR, LABEL_WINDOW = 0, 1, 2, 3


def clear_everything():
    for collection in (bpy.data.objects, bpy.data.meshes, bpy.data.lights, bpy.data.cameras,
                       bpy.data.materials):
        for item in list(collection):
            collection.remove(item)


def set_input(node, names, value):
    for name in names:
        if name in node.inputs:
            node.inputs[name].default_value = value
            return True
    return False


_materials = {}


def material(name, label):
    key = (name, label)
    if key in _materials:
        return _materials[key]
    spec = MATERIALS.get(name, {"base_color": [0.5, 0.5, 0.5], "secondary_color": [0.5, 0.5, 0.5],
                                "roughness": 0.5, "texture": "none", "texture_scale_m": 1.0})
    mat = bpy.data.materials.new("%s.%d" % (name, label))
    mat.pass_index = label
    mat.use_nodes = True
    nodes, links = mat.node_tree.nodes, mat.node_tree.links
    bsdf = nodes.get("Principled BSDF")
    base = tuple(spec["base_color"]) + (1.0,)
    second = tuple(spec["secondary_color"]) + (1.0,)
    set_input(bsdf, ["Base Color"], base)
    set_input(bsdf, ["Roughness"], spec["roughness"])
    if name == "glass":
        set_input(bsdf, ["Transmission Weight", "Transmission"], 1.0)
        set_input(bsdf, ["IOR"], 1.45)
        set_input(bsdf, ["Alpha"], 1.0)
    texture = spec["texture"]
    if texture != "none":
        coords = nodes.new("ShaderNodeTexCoord")
        scale = 1.0 / spec["texture_scale_m"]
        if texture == "tiles":
            tex = nodes.new("ShaderNodeTexBrick")
            tex.offset = 0.0
            set_input(tex, ["Color1"], base)
            set_input(tex, ["Color2"], base)
            set_input(tex, ["Mortar"], second)
            set_input(tex, ["Scale"], scale * 0.5)
            set_input(tex, ["Mortar Size"], 0.01)
            links.new(coords.outputs["Object"], tex.inputs["Vector"])
            links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        else:
            if texture == "wood":
                tex = nodes.new("ShaderNodeTexWave")
                set_input(tex, ["Distortion"], 4.0)
            else:
                tex = nodes.new("ShaderNodeTexNoise")
                set_input(tex, ["Detail"], 6.0 if texture in ("concrete", "carpet") else 2.0)
            set_input(tex, ["Scale"], scale)
            ramp = nodes.new("ShaderNodeValToRGB")
            ramp.color_ramp.elements[0].color = base
            ramp.color_ramp.elements[1].color = second
            links.new(coords.outputs["Object"], tex.inputs["Vector"])
            links.new(tex.outputs["Fac"], ramp.inputs["Fac"])
            links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    _materials[key] = mat
    return mat


class MeshBuilder:
    """Boxes and polygons collected into one mesh object, one material slot per part."""

    def __init__(self):
        self.verts, self.faces, self.face_slots, self.slots = [], [], [], []

    def slot(self, mat):
        if mat not in self.slots:
            self.slots.append(mat)
        return self.slots.index(mat)

    def box(self, origin, u, v, length, depth, z0, z1, mat):
        """Box from `origin` along unit u (length) and unit v (depth), z0..z1."""
        if length <= 1e-6 or depth <= 1e-6 or z1 - z0 <= 1e-6:
            return
        o = Vector((origin[0], origin[1], 0.0))
        u3, v3 = Vector((u[0], u[1], 0.0)), Vector((v[0], v[1], 0.0))
        base = len(self.verts)
        for z in (z0, z1):
            for p in (o, o + u3 * length, o + u3 * length + v3 * depth, o + v3 * depth):
                self.verts.append((p.x, p.y, z))
        quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
        # Keep outward normals whatever the handedness of (u, v).
        flip = u[0] * v[1] - u[1] * v[0] < 0
        s = self.slot(mat)
        for q in quads:
            self.faces.append(tuple(base + i for i in (reversed(q) if flip else q)))
            self.face_slots.append(s)

    def polygon(self, points, z, up, mat):
        base = len(self.verts)
        for p in points:
            self.verts.append((p[0], p[1], z))
        idx = list(range(base, base + len(points)))
        self.faces.append(tuple(idx if up else reversed(idx)))
        self.face_slots.append(self.slot(mat))

    def build(self, name, label):
        mesh = bpy.data.meshes.new(name)
        mesh.from_pydata(self.verts, [], self.faces)
        for mat in self.slots:
            mesh.materials.append(mat)
        for poly, s in zip(mesh.polygons, self.face_slots):
            poly.material_index = s
        mesh.update()
        obj = bpy.data.objects.new(name, mesh)
        obj.pass_index = label
        obj["asbuilt_label"] = label
        bpy.context.scene.collection.objects.link(obj)
        return obj


def casing(mb, a, u, inward, s, width, z0, z1, cw, mat):
    # The architrave on the room side of the wall, cw wide around s..s+width, z0..z1.
    depth = SETTINGS["casing_depth_m"]
    left = a + u * (s - cw)
    bottom = max(0.0, z0 - cw) if z0 > 0 else 0.0
    mb.box(left + inward * depth, u, -inward, cw, depth, bottom, z1 + cw, mat)
    mb.box(left + u * (width + cw) + inward * depth, u, -inward, cw, depth, bottom, z1 + cw, mat)
    mb.box(a + u * s + inward * depth, u, -inward, width, depth, z1, z1 + cw, mat)
    if z0 > 0:
        mb.box(a + u * s + inward * depth, u, -inward, width, depth, max(0.0, z0 - cw), z0, mat)


def portal(mb, a, u, out, s, width, z0, z1, label):
    # Label pass only: the opening's face on the wall's inner plane carries its
    # label, so a doorway or a window reads door or window whatever is seen
    # through it (DESIGN.md). Not in the photo.
    if not SETTINGS["labels_pass"]:
        return
    mb.box(a + u * s, u, out, width, 0.001, z0, z1, material("portal", label))


def build_room(ri, room):
    poly = [Vector(p) for p in room["polygon"]]
    n = len(poly)
    height, thick = room["height_m"], room["wall_thickness_m"]
    wall_mat = material(room["wall_material"], LABEL_WALL)
    skirting_mat = material("skirting", LABEL_WALL)
    dirs = [(poly[(i + 1) % n] - poly[i]).normalized() for i in range(n)]

    def cross(a, b):
        return a.x * b.y - a.y * b.x

    for w in range(n):
        a, u = poly[w], dirs[w]
        length = (poly[(w + 1) % n] - a).length
        out = Vector((u.y, -u.x))
        # Convex corners: extend outwards so the outer corner is closed.
        ext0 = 2.0 * thick if cross(dirs[w - 1], u) > 0 else 0.0
        ext1 = 2.0 * thick if cross(u, dirs[(w + 1) % n]) > 0 else 0.0
        ops = sorted([o for o in room["openings"] if o["wall"] == w], key=lambda o: o["offset_m"])
        mb = MeshBuilder()
        cursor = -ext0
        for o in ops:
            s, e = o["offset_m"], o["offset_m"] + o["width_m"]
            top = o["sill_m"] + o["height_m"]
            mb.box(a + u * cursor, u, out, s - cursor, thick, 0.0, height, wall_mat)
            mb.box(a + u * s, u, out, e - s, thick, 0.0, o["sill_m"], wall_mat)
            mb.box(a + u * s, u, out, e - s, thick, top, height, wall_mat)
            cursor = e
        mb.box(a + u * cursor, u, out, length + ext1 - cursor, thick, 0.0, height, wall_mat)
        if room["skirting"]:
            # Along the wall, stopping at door casings (and openings down to the floor).
            sd, sh = SETTINGS["skirting_depth_m"], SETTINGS["skirting_height_m"]
            cursor = 0.0
            for o in ops:
                if o["kind"] == "door" or o["sill_m"] < 0.1:
                    gap = SETTINGS["door_casing_m"] if o["kind"] == "door" else 0.0
                    mb.box(a + u * cursor - out * sd, u, out, o["offset_m"] - gap - cursor, sd, 0.0, sh,
                           skirting_mat)
                    cursor = o["offset_m"] + o["width_m"] + gap
            mb.box(a + u * cursor - out * sd, u, out, length - cursor, sd, 0.0, sh, skirting_mat)
        mb.build("wall.r%d.w%d" % (ri, w), LABEL_WALL)

        for k, o in enumerate(room["openings"]):
            if o["wall"] != w:
                continue
            s, width, sill, oh = o["offset_m"], o["width_m"], o["sill_m"], o["height_m"]
            inward = -out
            mb = MeshBuilder()
            if o["kind"] == "door":
                mat = material(o["material"] or "door", LABEL_DOOR)
                theta = math.radians(o["open_deg"])
                if o["hinge"] == "left":  # Seen from inside, the wall's end is on the left.
                    hinge, closed = a + u * (s + width), -u
                else:
                    hinge, closed = a + u * s, u
                leaf = closed * math.cos(theta) + inward * math.sin(theta)
                side = Vector((leaf.y, -leaf.x))  # Leaf thickness, towards the outside.
                if side.dot(out) < 0:
                    side = -side
                mb.box(hinge, leaf, side, width, 0.04, 0.0, oh, mat)
                casing(mb, a, u, inward, s, width, 0.0, oh, SETTINGS["door_casing_m"], mat)
                portal(mb, a, u, out, s, width, 0.0, oh, LABEL_DOOR)
                mb.build("door.r%d.o%d" % (ri, k), LABEL_DOOR)
            else:
                frame = material(o["material"] or "window_frame", LABEL_WINDOW)
                fw = o["frame_width_m"]
                depth = min(0.06, thick)
                mid = a + u * s + out * (0.5 * thick - 0.5 * depth)
                if fw > 0:
                    mb.box(mid, u, out, width, depth, sill, sill + fw, frame)
                    mb.box(mid, u, out, width, depth, sill + oh - fw, sill + oh, frame)
                    mb.box(mid, u, out, fw, depth, sill, sill + oh, frame)
                    mb.box(mid + u * (width - fw), u, out, fw, depth, sill, sill + oh, frame)
                if o["glass"]:
                    glass = material("glass", LABEL_WINDOW)
                    mb.box(mid + u * fw + out * (0.5 * depth - 0.003), u, out, width - 2 * fw, 0.006,
                           sill + fw, sill + oh - fw, glass)
                # Sill board through the wall and into the room, casing around.
                sb, so = SETTINGS["sill_board_m"], SETTINGS["sill_overhang_m"]
                mb.box(a + u * (s - so) + inward * so, u, out, width + 2 * so, thick + so, max(0.0, sill - sb), sill,
                       frame)
                casing(mb, a, u, inward, s, width, max(0.0, sill - sb), sill + oh, SETTINGS["window_casing_m"],
                       frame)
                portal(mb, a, u, out, s, width, sill, sill + oh, LABEL_WINDOW)
                mb.build("window.r%d.o%d" % (ri, k), LABEL_WINDOW)

    mb = MeshBuilder()
    mb.polygon(poly, 0.0, True, material(room["floor_material"], LABEL_OTHER))
    mb.build("floor.r%d" % ri, LABEL_OTHER)
    mb = MeshBuilder()
    mb.polygon(poly, height, False, material(room["ceiling_material"], LABEL_OTHER))
    mb.build("ceiling.r%d" % ri, LABEL_OTHER)


def build_furniture(i, f):
    yaw = math.radians(f["yaw_deg"])
    u = Vector((math.cos(yaw), math.sin(yaw)))
    v = Vector((-math.sin(yaw), math.cos(yaw)))
    w, d, h = f["size_m"]
    c = Vector(f["centre_m"])
    mb = MeshBuilder()
    mb.box(c - u * (w / 2) - v * (d / 2), u, v, w, d, f["elevation_m"], f["elevation_m"] + h,
           material(f["material"], LABEL_OTHER))
    mb.build("furniture.%d.%s" % (i, f["name"] or "box"), LABEL_OTHER)


def build_outside(env, rooms):
    xs = [p[0] for r in rooms for p in r["polygon"]]
    ys = [p[1] for r in rooms for p in r["polygon"]]
    cx, cy = 0.5 * (min(xs) + max(xs)), 0.5 * (min(ys) + max(ys))
    ground = bpy.data.materials.new("ground")
    ground.use_nodes = True
    set_input(ground.node_tree.nodes.get("Principled BSDF"), ["Base Color"], tuple(env["ground_color"]) + (1.0,))
    mb = MeshBuilder()
    mb.polygon([(cx - 200, cy - 200), (cx + 200, cy - 200), (cx + 200, cy + 200), (cx - 200, cy + 200)],
               -0.02, True, ground)
    mb.build("outside.ground", LABEL_OTHER)
    if env["exterior_objects"]:
        building = material("wall", LABEL_OTHER)
        tree = material("furniture", LABEL_OTHER)
        for k in range(8):
            ang = 2.0 * math.pi * k / 8.0 + 0.3
            dist = 14.0 + 5.0 * (k % 3)
            p = Vector((cx + dist * math.cos(ang), cy + dist * math.sin(ang)))
            tangent = Vector((-math.sin(ang), math.cos(ang)))
            radial = Vector((math.cos(ang), math.sin(ang)))
            mb = MeshBuilder()
            if k % 2 == 0:
                mb.box(p - tangent * 4.0, tangent, radial, 8.0, 6.0, 0.0, 6.0 + 3.0 * (k % 3), building)
            else:
                mb.box(p - tangent * 0.8, tangent, radial, 1.6, 1.6, 0.0, 5.0, tree)
            mb.build("outside.%d" % k, LABEL_OTHER)


def build_lights(lights):
    for i, l in enumerate(lights):
        kind = l["kind"]
        if kind == "area":
            data = bpy.data.lights.new("light.%d" % i, "AREA")
            data.shape = "RECTANGLE"
            data.size, data.size_y = l["size_m"]
            data.energy = 60.0 * l["intensity"] * l["size_m"][0] * l["size_m"][1]
        elif kind == "point":
            data = bpy.data.lights.new("light.%d" % i, "POINT")
            data.energy = 60.0 * l["intensity"]
        else:
            data = bpy.data.lights.new("light.%d" % i, "SUN")
            data.energy = 2.0 * l["intensity"]
        data.color = l["color"]
        obj = bpy.data.objects.new("light.%d" % i, data)
        obj.location = l["position_m"]
        if kind == "sun":
            az, el = math.radians(l["azimuth_deg"]), math.radians(l["elevation_deg"])
            toward_sun = Vector((math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)))
            obj.rotation_euler = toward_sun.to_track_quat("Z", "Y").to_euler()
        bpy.context.scene.collection.objects.link(obj)


def build_world(env):
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    bg = world.node_tree.nodes.get("Background")
    colour = tuple(env["sky_color"]) if env["sky"] else (0.0, 0.0, 0.0)
    set_input(bg, ["Color"], colour + (1.0,))
    set_input(bg, ["Strength"], 0.5 + env["ambient"])
    bpy.context.scene.world = world


def build_panorama_camera(views, width):
    # Cycles' equirectangular image centre looks along the camera's −Z; the
    # pano frame's centre column looks along −Y (yaw 180°), its left edge +Y.
    scene = bpy.context.scene
    data = bpy.data.cameras.new("pano")
    data.type = "PANO"
    if hasattr(data, "panorama_type"):
        data.panorama_type = "EQUIRECTANGULAR"
    else:
        data.cycles.panorama_type = "EQUIRECTANGULAR"
    data.clip_start, data.clip_end = 0.05, 500.0
    cam = bpy.data.objects.new("pano", data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    cam.location = views[0]["position_m"]
    cam.rotation_euler = (math.radians(90.0), 0.0, math.radians(180.0))
    render = scene.render
    render.resolution_x, render.resolution_y, render.resolution_percentage = width, width // 2, 100
    render.use_multiview = False
    render.image_settings.file_format = "PNG"
    render.image_settings.color_mode = "RGB"
    scene.frame_start, scene.frame_end = 1, 1
    scene.frame_set(1)


def build_camera(rig, views):
    if SETTINGS["panorama_width_px"] > 0:
        build_panorama_camera(views, SETTINGS["panorama_width_px"])
        return
    scene = bpy.context.scene
    data = bpy.data.cameras.new("rig")
    data.sensor_fit = "HORIZONTAL"
    data.sensor_width = SETTINGS["sensor_width_mm"]
    w, h = rig["width_px"], rig["height_px"]
    data.lens = rig["fx"] * data.sensor_width / w
    # OpenCV principal point (pixel centres at integers) → Blender shift (fractions of the width).
    data.shift_x = ((w - 1) / 2.0 - rig["cx"]) / w
    data.shift_y = (rig["cy"] - (h - 1) / 2.0) / w
    data.clip_start, data.clip_end = 0.05, 500.0
    data.stereo.convergence_mode = "PARALLEL"
    data.stereo.interocular_distance = rig["baseline_m"]
    data.stereo.pivot = "CENTER"
    cam = bpy.data.objects.new("rig", data)
    scene.collection.objects.link(cam)
    scene.camera = cam
    render = scene.render
    render.resolution_x, render.resolution_y, render.resolution_percentage = w, h, 100
    if abs(rig["fy"] - rig["fx"]) > 1e-6 * rig["fx"]:
        print("asbuilt: warning: fy != fx; Blender renders square pixels (fx used)")
    render.use_multiview = True
    render.views_format = "STEREO_3D"
    render.image_settings.views_format = "INDIVIDUAL"
    render.image_settings.file_format = "PNG"
    render.image_settings.color_mode = "RGB"
    # Camera looks along local −Z with +Y up: rotate X by 90° + pitch to look
    # along +Y (yaw 0), then Z by yaw (DESIGN.md: counter-clockwise).
    for i, v in enumerate(views):
        cam.location = v["position_m"]
        cam.rotation_euler = (math.radians(90.0 + v["pitch_deg"]), 0.0, math.radians(v["yaw_deg"]))
        cam.keyframe_insert("location", frame=i + 1)
        cam.keyframe_insert("rotation_euler", frame=i + 1)
    if cam.animation_data and cam.animation_data.action:
        for fc in cam.animation_data.action.fcurves:
            for kp in fc.keyframe_points:
                kp.interpolation = "CONSTANT"
    scene.frame_start, scene.frame_end = 1, max(1, len(views))
    scene.frame_set(1)


def cycles_has_denoiser():
    # Builds without OpenImageDenoise (Debian's Blender 3.4, say) stop the
    # render with "Build without OpenImageDenoiser" when denoising is on.
    try:
        import _cycles
    except ImportError:
        return False
    return bool(getattr(_cycles, "with_openimagedenoise", False))


def setup_render():
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = SETTINGS["samples"]
    denoise = SETTINGS["denoise"]
    if denoise and not cycles_has_denoiser():
        print("asbuilt: note: this Blender build has no OpenImageDenoise; rendering without denoising "
              "(expect more noise; raise the samples to compensate)")
        denoise = False
    scene.cycles.use_denoising = denoise
    scene.view_settings.view_transform = "Standard"
    if SETTINGS["labels_pass"]:
        # Each pixel's one sample at its centre: the surface the centre sees.
        scene.cycles.samples = 1
        scene.cycles.use_adaptive_sampling = False
        scene.cycles.use_denoising = False
        scene.cycles.filter_width = 0.01
        scene.cycles.max_bounces = 0
    layer = scene.view_layers[0]
    layer.use_pass_object_index = True
    layer.use_pass_material_index = True
    layer.use_pass_z = True
    if not SETTINGS["index_pass"]:
        return
    scene.use_nodes = True
    tree = scene.node_tree
    for node in list(tree.nodes):
        tree.nodes.remove(node)
    layers = tree.nodes.new("CompositorNodeRLayers")
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(layers.outputs["Image"], composite.inputs["Image"])
    out = tree.nodes.new("CompositorNodeOutputFile")
    out.name = "asbuilt_index"
    out.format.file_format = "OPEN_EXR"
    out.format.color_depth = "32"
    out.file_slots[0].path = "index_"
    tree.links.new(layers.outputs["IndexOB"], out.inputs[0])

    def index_path(scene_arg, *unused):
        node = scene_arg.node_tree.nodes.get("asbuilt_index") if scene_arg.node_tree else None
        if node is not None:
            node.base_path = os.path.join(bpy.path.abspath(scene_arg.render.filepath), "index")

    bpy.app.handlers.render_init.append(index_path)


clear_everything()
for ri, room in enumerate(SCENE["rooms"]):
    build_room(ri, room)
for i, f in enumerate(SCENE["furniture"]):
    build_furniture(i, f)
build_outside(SCENE["environment"], SCENE["rooms"])
build_lights(SCENE["lights"])
build_world(SCENE["environment"])
build_camera(RIG, VIEWS)
setup_render()
print("asbuilt: built %d objects, %d frames" % (len(bpy.data.objects), len(VIEWS)))
)PY";

// JSON text safe inside a Python r'''…''' literal: ASCII only, and no
// single quotes (JSON allows \u0027 for them).
std::string PythonJsonLiteral(const nlohmann::json& j) {
  std::string text = j.dump(-1, ' ', /*ensure_ascii=*/true);
  std::string out;
  for (char c : text) {
    if (c == '\'') {
      out += "\\u0027";
    } else {
      out += c;
    }
  }
  return "json.loads(r'''" + out + "''')";
}

}  // namespace

void BlenderExportOptions::Check() const {
  CheckArgument(samples > 0, fmt::format("BlenderExportOptions.samples = {}, must be > 0", samples));
  CheckArgument(sensor_width_mm > 0,
                fmt::format("BlenderExportOptions.sensor_width_mm = {}, must be > 0", sensor_width_mm));
  CheckArgument(panorama_width_px == 0 || (panorama_width_px >= 16 && panorama_width_px % 2 == 0),
                fmt::format("BlenderExportOptions.panorama_width_px = {}, must be 0 (stereo pairs) or an even "
                            "width >= 16",
                            panorama_width_px));
}

std::string BlenderExportSummary::BriefReport() const {
  if (panorama) return fmt::format("{} objects, {} lights, 1 frame (360° panorama)", objects, lights);
  return fmt::format("{} objects, {} lights, {} frames (stereo pairs)", objects, lights, frames);
}

std::string BlenderScript(const Scene& scene, const BlenderExportOptions& options, BlenderExportSummary* summary) {
  options.Check();
  nlohmann::json materials = nlohmann::json::object();
  // Materials: every built-in (as the scene overrides it), then the scene's own.
  for (const Material& m : BuiltinMaterials()) {
    if (!materials.contains(m.name)) {
      const Material* found = FindMaterial(scene, m.name);
      const Material& use = found ? *found : m;
      materials[m.name] = {
          {"base_color", {use.base_color.x(), use.base_color.y(), use.base_color.z()}},
          {"secondary_color", {use.secondary_color.x(), use.secondary_color.y(), use.secondary_color.z()}},
          {"roughness", use.roughness},
          {"texture", TextureKindName(use.texture)},
          {"texture_scale_m", use.texture_scale_m}};
    }
  }
  for (const Material& m : scene.materials) {
    materials[m.name] = {{"base_color", {m.base_color.x(), m.base_color.y(), m.base_color.z()}},
                         {"secondary_color", {m.secondary_color.x(), m.secondary_color.y(), m.secondary_color.z()}},
                         {"roughness", m.roughness},
                         {"texture", TextureKindName(m.texture)},
                         {"texture_scale_m", m.texture_scale_m}};
  }
  nlohmann::json views = nlohmann::json::array();
  for (const Viewpoint& v : ResolveViewpoints(scene)) {
    views.push_back({{"position_m", {v.position_m.x(), v.position_m.y(), v.position_m.z()}},
                     {"yaw_deg", v.yaw_deg},
                     {"pitch_deg", v.pitch_deg}});
  }
  PinholeCamera cam = scene.rig.Camera();
  nlohmann::json rig = {{"width_px", cam.width_px},
                        {"height_px", cam.height_px},
                        {"fx", cam.fx},
                        {"fy", cam.fy},
                        {"cx", cam.cx},
                        {"cy", cam.cy},
                        {"baseline_m", scene.rig.baseline_m}};
  nlohmann::json settings = {{"samples", options.samples},
                             {"denoise", options.denoise},
                             {"index_pass", options.index_pass},
                             {"sensor_width_mm", options.sensor_width_mm},
                             {"panorama_width_px", options.panorama_width_px},
                             {"labels_pass", options.labels_pass},
                             {"skirting_depth_m", kSkirtingDepthM},
                             {"skirting_height_m", kSkirtingHeightM},
                             {"door_casing_m", kDoorCasingM},
                             {"window_casing_m", kWindowCasingM},
                             {"casing_depth_m", kCasingDepthM},
                             {"sill_board_m", kSillBoardM},
                             {"sill_overhang_m", kSillOverhangM}};

  if (summary) {
    int objects = 0;
    for (const Room& r : scene.rooms) objects += WallCount(r) + static_cast<int>(r.openings.size()) + 2;
    objects += static_cast<int>(scene.furniture.size()) + 1 + (scene.environment.exterior_objects ? 8 : 0);
    summary->objects = objects;
    summary->lights = static_cast<int>(scene.lights.size());
    summary->panorama = options.panorama_width_px > 0;
    summary->frames = summary->panorama ? 1 : static_cast<int>(views.size());
  }

  std::string out;
  out += "# Blender 3.x/4.x script written by `asbuilt scene export-blender` for scene \"" + [&] {
    std::string n;
    for (char c : scene.name) n += (c == '\n' || c == '\r') ? ' ' : c;
    return n;
  }() + "\".\n";
  if (options.panorama_width_px > 0) {
    out += "# Render the 360° panorama:          blender -b -P build.py -o OUT/ -f 1\n";
  } else {
    out += "# Render every view's stereo pair:  blender -b -P build.py -o OUT/ -a\n";
    out += "# One view (frame N = view N-1):    blender -b -P build.py -o OUT/ -f N\n";
  }
  out += "# Object and material pass index = label id (0 other, 1 wall, 2 door, 3 window).\n";
  out += "import json\n\n";
  out += "SCENE = " + PythonJsonLiteral(SceneToJson(scene)) + "\n";
  out += "MATERIALS = " + PythonJsonLiteral(materials) + "\n";
  out += "VIEWS = " + PythonJsonLiteral(views) + "\n";
  out += "RIG = " + PythonJsonLiteral(rig) + "\n";
  out += "SETTINGS = " + PythonJsonLiteral(settings) + "\n";
  out += kBuilder;
  return out;
}

BlenderExportSummary WriteBlenderScript(const Scene& scene, const BlenderExportOptions& options,
                                        const std::filesystem::path& path) {
  BlenderExportSummary summary;
  std::string script = BlenderScript(scene, options, &summary);
  WriteFileAtomic(path, script);
  return summary;
}

}  // namespace asbuilt
