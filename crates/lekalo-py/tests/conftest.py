import os

from hypothesis import settings

# Property tests run a fixed number of examples without deadlines (the shared 2-core machines
# that run CI are too noisy for per-example timing).
settings.register_profile("ci", max_examples=60, deadline=None, derandomize=True, database=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
