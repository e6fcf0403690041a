"""Shared set-up of the pvpython tests: find and load the ASM plugin.

Environment (set by CTest, see CMakeLists.txt):
  ASM_PLUGIN    path of the plugin library (or give it as the first argument)
  ASM_DATA_DIR  Testing/Data
"""
import os
import sys

from paraview.simple import LoadPlugin


def load_asm_plugin(test_name, namespace):
    """Load the plugin's proxies into `namespace`; return the data directory."""
    here = os.path.dirname(os.path.abspath(__file__))
    plugin = sys.argv[1] if len(sys.argv) > 1 else os.environ.get("ASM_PLUGIN")
    if not plugin or not os.path.isfile(plugin):
        sys.exit("%s: plugin not found (ASM_PLUGIN=%r)" % (test_name, plugin))
    LoadPlugin(plugin, ns=namespace)
    print("loaded plugin", plugin)
    return os.environ.get("ASM_DATA_DIR", os.path.join(here, "..", "Data"))
