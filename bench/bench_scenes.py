"""The scenes the bench scripts measure by default, for `import bench_scenes` from bench/*.py: the seven whose
speed docs/PERFORMANCE.md tracks (bunny, car, killeroo_2020, dragon_lowres, monkey of the conformance set;
grid_large and mirror_scene of the peer scenes). RAYVIEW_SHARED_DIR overrides where shared/ is (default: beside the
repository)."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("RAYVIEW_SHARED_DIR", os.path.join(ROOT, "..", "shared"))
CONFORMANCE = os.path.join(SHARED, "conformance", "ceng477")
PEER = os.path.join(SHARED, "peer-scenes", "mertugr__mesh-trace", "scenes")
SEVEN = [os.path.join(CONFORMANCE, n + ".xml") for n in ("bunny", "car", "killeroo_2020", "dragon_lowres", "monkey")] + \
        [os.path.join(PEER, n + ".xml") for n in ("grid_large", "mirror_scene")]


def name(scene):
    """bunny for .../bunny.xml."""
    return os.path.splitext(os.path.basename(scene))[0]
