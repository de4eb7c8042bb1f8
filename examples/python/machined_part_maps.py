# %% [markdown]
# # Exact depth and normal maps of the machined part
#
# A notebook in the "percent" format (Jupyter, VS Code and Spyder open its `# %%` cells as
# cells; `python3 examples/python/machined_part_maps.py` runs it whole). It renders
# `examples/machined_part.uq` with the exact raycast engine through the `quadrix` module and
# saves the picture, a depth map and a normal map as PNG files. Run from the repository root
# with the module on the path:
#
#     PYTHONPATH=build/python python3 examples/python/machined_part_maps.py [OUT_DIR]

# %%
import os
import sys

import numpy as np

import quadrix

here = os.path.dirname(os.path.abspath(__file__))
scene_path = os.path.join(here, "..", "machined_part.uq")
out_dir = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(out_dir, exist_ok=True)

# %% [markdown]
# Read the scene (errors would raise `quadrix.SceneError` with file, line and column) and look
# at what it holds.

# %%
scene = quadrix.read(scene_path)
print("solids drawn:", [s["id"] for s in scene.solids() if s["drawn"]])
print("views:", scene.views(), " engines:", quadrix.engines())

# %% [markdown]
# Render. `frame.image`, `frame.depth`, `frame.normals` and the id arrays are NumPy arrays over
# the Frame's own memory (no copy).

# %%
frame = scene.render(size=(640, 480), engine="raycast")
print(frame, "covered pixels:", frame.stats["covered_pixels"],
      f"render {frame.stats['render_seconds']:.3f} s")
frame.save(os.path.join(out_dir, "part.png"))

# %% [markdown]
# The depth map: device z (pixels, growing away from the viewer; +inf where nothing is drawn),
# mapped to 8 bits with near = white and the background black.

# %%
depth = frame.depth
hit = np.isfinite(depth)
near, far = depth[hit].min(), depth[hit].max()
gray = np.zeros(depth.shape, np.uint8)
gray[hit] = np.round(255 - 200 * (depth[hit] - near) / max(far - near, 1e-12)).astype(np.uint8)
quadrix.write_png(os.path.join(out_dir, "part_depth.png"), gray)
print(f"depth: {near:.2f} .. {far:.2f} pixels")

# %% [markdown]
# The normal map: unit world-space normals as the usual RGB encoding (n + 1) / 2.

# %%
normals = frame.normals
rgb = np.where(hit[..., None], np.round((normals + 1) * 127.5), 0).astype(np.uint8)
quadrix.write_png(os.path.join(out_dir, "part_normals.png"), rgb)

# %% [markdown]
# Ids: which solid and which surface each pixel shows.

# %%
surfaces, counts = np.unique(frame.surface[hit], return_counts=True)
top = sorted(zip(counts, surfaces), reverse=True)[:5]
print("largest surfaces:", [(frame.surface_names[s], int(c)) for c, s in top])
print("wrote", ", ".join(os.path.join(out_dir, n)
                         for n in ("part.png", "part_depth.png", "part_normals.png")))
