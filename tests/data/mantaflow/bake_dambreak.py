# Headless Blender: a Mantaflow FLIP dam break (a block of water released at one end of a closed box),
# its particles in OpenVDB, for checking spume against a real FLIP cache that reseeds.
# Usage: blender -b -P bake_dambreak.py -- OUTDIR RES FRAMES
import bpy, sys, os, time
args = sys.argv[sys.argv.index("--") + 1:]
out_dir, resolution, frames = os.path.abspath(args[0]), int(args[1]), int(args[2])
os.makedirs(out_dir, exist_ok=True)
bpy.ops.wm.read_factory_settings(use_empty=True)
scene = bpy.context.scene
scene.frame_start, scene.frame_end = 1, frames
scene.render.fps = 25
bpy.ops.mesh.primitive_cube_add(size=1, location=(0.5, 0.25, 0.3))
domain = bpy.context.active_object
domain.scale = (1.0, 0.5, 0.6)
settings = domain.modifiers.new("Fluid", "FLUID")
settings.fluid_type = "DOMAIN"
ds = settings.domain_settings
ds.domain_type = "LIQUID"
ds.resolution_max = resolution
ds.cache_directory = out_dir
ds.cache_type = "ALL"
ds.cache_data_format = "OPENVDB"
ds.cache_frame_start, ds.cache_frame_end = 1, frames
ds.use_flip_particles = True
ds.use_mesh = False
# The water: 0.3 m long, the box's full width, 0.4 m high, against the -x wall.
bpy.ops.mesh.primitive_cube_add(size=1, location=(0.15, 0.25, 0.2))
block = bpy.context.active_object
block.scale = (0.3, 0.5, 0.4)
flow = block.modifiers.new("Fluid", "FLUID")
flow.fluid_type = "FLOW"
flow.flow_settings.flow_type = "LIQUID"
flow.flow_settings.flow_behavior = "GEOMETRY"
start = time.time()
with bpy.context.temp_override(object=domain, active_object=domain, scene=scene):
    result = bpy.ops.fluid.bake_all()
print("BAKE", result, "%.1f s" % (time.time() - start))
