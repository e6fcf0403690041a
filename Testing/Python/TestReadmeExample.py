"""pvpython test: the complete pvpython example of README.md ("Using it from
pvpython / pvbatch") runs as printed, with the plugin path and the data
directory of this build, in a scratch directory.

Set-up (plugin and data paths): asm_test_setup.py.
"""
import os
import re
import tempfile

from asm_test_setup import load_asm_plugin

here = os.path.dirname(os.path.abspath(__file__))
data_dir = os.path.abspath(load_asm_plugin("TestReadmeExample", globals()))
readme = open(os.path.join(here, "..", "..", "README.md")).read()
blocks = [b for b in re.findall(r"```python\n(.*?)```", readme, re.S) if "KeyPointError(Original" in b]
assert len(blocks) == 1, "README.md: expected one pvpython example with KeyPointError, found %d" % len(blocks)
code = blocks[0]
assert 'LoadPlugin("build/lib/paraview-5.11/plugins/ASM/ASM.so"' in code
code = code.replace('"build/lib/paraview-5.11/plugins/ASM/ASM.so"', repr(os.environ["ASM_PLUGIN"]))
code = code.replace('"Testing/Data/', '"' + data_dir + '/')

os.chdir(tempfile.mkdtemp(prefix="asm-readme-"))
scope = {}
exec(compile(code, "README.md example", "exec"), scope)
assert scope["cloud"].GetNumberOfPoints() == 1797, scope["cloud"].GetNumberOfPoints()
assert os.path.getsize("bunny-5pct.vtp") > 0
assert scope["figures"].GetColumnByName("MKPE").GetValue(0) > 0
print("TestReadmeExample: OK")
