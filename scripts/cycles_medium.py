# Blender (3.4, Cycles) side of scripts/crosscheck-cycles.sh: renders kiri's medium.vdb with
# Cycles in kiri's units, and compares linear EXR images. Run headless:
#
#   blender -b --factory-startup --python scripts/cycles_medium.py -- render SCENE.json AUTHOR_DIR OUT.exr
#       [--camera NAME] [--width W] [--height H] [--samples N] [--bounces N] [--ground] [--no-offset]
#   blender -b --factory-startup --python scripts/cycles_medium.py -- compare A.exr B.exr [--block 4]
#
# Units (docs/medium.md, "Against a path tracer"): the grid "density" is sigma_t in 1/m (scene
# unit the metre); a Principled Volume with Density 1, Color = albedo, Absorption Color black and
# Anisotropy = g scatters sigma_s = albedo sigma_t and absorbs the rest. kiri's sun (colour x
# intensity: the radiance of a white Lambertian surface facing it) is a Sun light of Strength
# pi x intensity and colour `color`, angle 0 (a directional light). The world is black (kiri
# render --no-sky); --ground brings the terrain from AUTHOR_DIR/layers.glb as a black surface
# that hides and shadows (kiri render --black-ground); without it nothing is below the fog but
# the black world. Cycles samples a VDB grid half a voxel off OpenVDB's convention (voxel i at
# index i + 1/2; docs/references.md, library facts), so the volume object moves by -v/2 on every
# axis unless --no-offset. Pixels are sampled at their centres (a box filter 0.01 px wide), as
# kiri's CPU renderers do.
import json
import math
import os
import sys

import bpy
import numpy as np
from mathutils import Vector


def fail(message):
    print("cycles_medium: " + message, file=sys.stderr)
    sys.exit(2)


def options(args, flags, values):
    """Splits args into positionals, flags (set) and --key value pairs (dict)."""
    positional, found, pairs = [], set(), {}
    i = 0
    while i < len(args):
        a = args[i]
        if a in flags:
            found.add(a)
        elif a in values:
            if i + 1 >= len(args):
                fail(a + " needs a value")
            pairs[a] = args[i + 1]
            i += 1
        elif a.startswith("--"):
            fail("unknown option " + a)
        else:
            positional.append(a)
        i += 1
    return positional, found, pairs


def look_at(obj, eye, target):
    obj.location = eye
    obj.rotation_mode = "QUATERNION"
    obj.rotation_quaternion = (Vector(target) - Vector(eye)).to_track_quat("-Z", "Y")


def render(args):
    positional, flags, pairs = options(
        args, {"--ground", "--no-offset"}, {"--camera", "--width", "--height", "--samples", "--bounces", "--seed"})
    if len(positional) != 3:
        fail("render SCENE.json AUTHOR_DIR OUT.exr [options]")
    scene_path, author_dir, out = positional
    with open(scene_path) as f:
        scene = json.load(f)
    with open(os.path.join(author_dir, "report.json")) as f:
        optics = json.load(f)["optics"]
    cameras = scene.get("cameras", [])
    if not cameras:
        fail(scene_path + ": the cross-check needs a camera in the scene")
    name = pairs.get("--camera")
    camera = next((c for c in cameras if c.get("name", "default") == name), None) if name else cameras[0]
    if camera is None:
        fail(scene_path + ": no camera named " + name)
    sun = scene.get("sun", {})
    sun_direction = Vector(sun.get("direction", [0.5, -0.3, 0.6])).normalized()
    sun_colour = sun.get("color", [1.0, 0.96, 0.9])
    sun_intensity = float(sun.get("intensity", 3.0))

    bpy.ops.wm.read_factory_settings(use_empty=True)
    sc = bpy.context.scene
    sc.render.engine = "CYCLES"
    cy = sc.cycles
    cy.device = "CPU"
    cy.samples = int(pairs.get("--samples", 256))
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.seed = int(pairs.get("--seed", 1))
    bounces = int(pairs.get("--bounces", 128))
    cy.max_bounces = bounces
    cy.volume_bounces = bounces
    cy.diffuse_bounces = bounces
    cy.glossy_bounces = 0
    cy.transmission_bounces = bounces
    # The volume's bounding mesh counts as a transparent surface: shadow rays to the sun cross it.
    cy.transparent_max_bounces = bounces
    cy.sample_clamp_direct = 0.0
    cy.sample_clamp_indirect = 0.0
    cy.use_volume_guiding = False
    cy.volume_step_rate = 0.5
    cy.volume_max_steps = 4096
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 0.01
    sc.render.resolution_x = int(pairs.get("--width", 160))
    sc.render.resolution_y = int(pairs.get("--height", 90))
    sc.render.resolution_percentage = 100
    sc.render.film_transparent = False
    sc.view_settings.view_transform = "Standard"
    sc.render.image_settings.file_format = "OPEN_EXR"
    sc.render.image_settings.color_depth = "32"
    sc.render.image_settings.color_mode = "RGBA"

    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    sc.world = world

    cam = bpy.data.cameras.new("kiri")
    cam.sensor_fit = "VERTICAL"
    cam.sensor_height = 24.0
    cam.lens = 12.0 / math.tan(math.radians(float(camera.get("fov", 45.0))) / 2.0)
    cam.clip_start = 0.1
    cam.clip_end = 1e6
    cam_obj = bpy.data.objects.new("kiri", cam)
    sc.collection.objects.link(cam_obj)
    look_at(cam_obj, camera["position"], camera["target"])
    sc.camera = cam_obj

    light = bpy.data.lights.new("sun", "SUN")
    light.energy = math.pi * sun_intensity  # irradiance, W/m^2: pi x the Lambertian radiance
    light.color = sun_colour
    light.angle = 0.0
    light_obj = bpy.data.objects.new("sun", light)
    sc.collection.objects.link(light_obj)
    light_obj.rotation_mode = "QUATERNION"
    light_obj.rotation_quaternion = sun_direction.to_track_quat("Z", "Y")  # it shines along -Z

    bpy.ops.object.volume_import(filepath=os.path.join(author_dir, "medium.vdb"))
    vol = bpy.context.active_object
    vol.data.grids.load()
    grid = vol.data.grids["density"]
    voxel = Vector(grid.matrix_object.col[0][:3]).length
    if "--no-offset" not in flags:
        vol.location = (-0.5 * voxel, -0.5 * voxel, -0.5 * voxel)
    vol.data.render.clipping = 0.0  # the default 0.001 1/m would drop the fog's thin top
    vol.data.render.precision = "FULL"
    vol.data.render.space = "WORLD"
    vol.data.render.step_size = 0.0
    mat = bpy.data.materials.new("fog")
    mat.use_nodes = True
    nodes = mat.node_tree.nodes
    nodes.clear()
    out_node = nodes.new("ShaderNodeOutputMaterial")
    pv = nodes.new("ShaderNodeVolumePrincipled")
    albedo = float(optics["albedo"])
    pv.inputs["Color"].default_value = (albedo, albedo, albedo, 1.0)
    pv.inputs["Density"].default_value = 1.0
    pv.inputs["Density Attribute"].default_value = "density"
    pv.inputs["Anisotropy"].default_value = float(optics["anisotropy_g"])
    pv.inputs["Absorption Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    pv.inputs["Emission Strength"].default_value = 0.0
    pv.inputs["Blackbody Intensity"].default_value = 0.0
    mat.node_tree.links.new(pv.outputs["Volume"], out_node.inputs["Volume"])
    vol.data.materials.append(mat)

    if "--ground" in flags:
        # Debian's Blender 3.4 glTF importer still uses np.bool, which numpy 1.24 removed.
        if not hasattr(np, "bool"):
            np.bool = bool
        bpy.ops.import_scene.gltf(filepath=os.path.join(author_dir, "layers.glb"))
        black = bpy.data.materials.new("black ground")
        black.use_nodes = True
        bsdf = black.node_tree.nodes["Principled BSDF"]
        bsdf.inputs["Base Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        bsdf.inputs["Specular"].default_value = 0.0
        for obj in list(bpy.data.objects):
            if obj.type != "MESH":
                continue
            if obj.name.startswith("terrain"):
                obj.data.materials.clear()
                obj.data.materials.append(black)
                lo = [min((obj.matrix_world @ Vector(c))[i] for c in obj.bound_box) for i in range(3)]
                hi = [max((obj.matrix_world @ Vector(c))[i] for c in obj.bound_box) for i in range(3)]
                print("cycles_medium: terrain from %s to %s" % (["%.1f" % v for v in lo], ["%.1f" % v for v in hi]))
            else:
                bpy.data.objects.remove(obj, do_unlink=True)
    print("cycles_medium: voxel %.4g m, offset %s, sun strength %.4g, albedo %.4g, g %.4g, %d samples, %d bounces"
          % (voxel, "no" if "--no-offset" in flags else "-v/2", light.energy, albedo, float(optics["anisotropy_g"]),
             cy.samples, bounces))
    sc.render.filepath = out
    bpy.ops.render.render(write_still=True)
    if not os.path.exists(out):
        fail(out + ": Cycles wrote no image")


def luminance_image(path):
    img = bpy.data.images.load(os.path.abspath(path), check_existing=False)
    w, h = img.size
    px = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(px)
    px = px.reshape(h, w, 4).astype(np.float64)
    return 0.2126 * px[..., 0] + 0.7152 * px[..., 1] + 0.0722 * px[..., 2]


def compare(args):
    positional, _, pairs = options(args, set(), {"--block"})
    if len(positional) != 2:
        fail("compare A.exr B.exr [--block N]")
    a, b = (luminance_image(p) for p in positional)
    if a.shape != b.shape:
        fail("the images differ in size: %s and %s" % (a.shape, b.shape))
    n = int(pairs.get("--block", 4))
    h, w = (a.shape[0] // n) * n, (a.shape[1] // n) * n
    ba = a[:h, :w].reshape(h // n, n, w // n, n).mean(axis=(1, 3))
    bb = b[:h, :w].reshape(h // n, n, w // n, n).mean(axis=(1, 3))
    lit = bb > 1e-6 * max(bb.max(), 1e-30)
    rel = np.abs(ba[lit] - bb[lit]) / bb[lit]
    signed = (ba[lit] - bb[lit]) / bb[lit]
    print("mean %.6g / %.6g  ratio %.4f  %dx%d-block error: mean %.2f %%, median %.2f %%, mean signed %+.2f %%"
          % (a.mean(), b.mean(), a.mean() / b.mean() if b.mean() > 0 else float("nan"), n, n, 100 * rel.mean(),
             100 * np.median(rel), 100 * signed.mean()))


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if not argv or argv[0] not in ("render", "compare"):
        fail("usage: blender -b --python cycles_medium.py -- render|compare ...")
    (render if argv[0] == "render" else compare)(argv[1:])


main()
