"""The installed Python module loads from the prefix's site folder (argv[1]) and runs a call."""

import os
import sys

import trigrav

site = os.path.realpath(sys.argv[1])
assert os.path.dirname(os.path.realpath(trigrav.__file__)) == site, trigrav.__file__
assert os.path.isfile(os.path.join(site, "trigrav.pyi"))
scene = trigrav.generate_synthetic_scene(trigrav.SyntheticSceneOptions(num_points=50), 1)
estimate = trigrav.initialize_and_refine(trigrav.to_observations(scene))
assert estimate.success, estimate.message
print("import trigrav from", trigrav.__file__, "- initialize_and_refine:", estimate)
