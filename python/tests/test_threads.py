# SPDX-License-Identifier: MIT
"""The module's OpenMP wait policy: passive unless the user chose one (docs/python.md, Threads)."""
import os
import subprocess
import sys
import unittest

# libgomp prints its settings when it loads (OMP_DISPLAY_ENV; verbose: GOMP_SPINCOUNT, the
# spins before a thread sleeps, 0 when passive); the environment after the import is the user's.
PROBE = "import os, meshmorph; print('after:', os.environ.get('OMP_WAIT_POLICY'))"


def import_meshmorph(**env):
    base = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    run = subprocess.run([sys.executable, "-c", PROBE], env={**base, "OMP_DISPLAY_ENV": "verbose", **env},
                         capture_output=True, text=True, check=True)
    return run.stdout + run.stderr


class ThreadsTest(unittest.TestCase):
    def test_passive_by_default_and_the_environment_left_as_it_was(self):
        out = import_meshmorph()
        self.assertIn("OMP_WAIT_POLICY = 'PASSIVE'", out)
        self.assertIn("GOMP_SPINCOUNT = '0'", out)
        self.assertIn("after: None", out)

    def test_the_users_policy_is_kept(self):
        out = import_meshmorph(OMP_WAIT_POLICY="active")
        self.assertIn("OMP_WAIT_POLICY = 'ACTIVE'", out)
        self.assertIn("after: active", out)
        self.assertIn("GOMP_SPINCOUNT = '300000'", import_meshmorph(GOMP_SPINCOUNT="300000"))


if __name__ == "__main__":
    unittest.main()
