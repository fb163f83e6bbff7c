"""Run by test_fmpy_logging.py in a child process (a segmentation fault must not kill pytest):
three instances made with a Python logger and freed, then an instance with fmpy's default
callbacks whose fmi2SetReal fails, so that riser logs an error through fmpy's native proxy.
argv: FMU, "raw" (fmpy's instantiate_fmu) or "kept" (riser_tools.fmpy_logging)."""
import gc, sys
from fmpy import read_model_description, extract
from fmpy.fmi2 import FMU2Slave
from fmpy.simulation import instantiate_fmu
fmu_path = sys.argv[1]; mode = sys.argv[2]
d = extract(fmu_path)
md = read_model_description(d)
msgs = []
def make(i):
    def logger(env, name, status, cat, message):
        msgs.append(message)
    if mode == "raw":
        f = instantiate_fmu(d, md, "CoSimulation", logger=logger)
    else:
        from riser_tools.fmpy_logging import instantiate_logged
        f = instantiate_logged(d, md, logger)
    f.freeInstance()
for i in range(3):
    make(i)
gc.collect()
junk = [bytearray(64) for _ in range(100000)]  # reuse the freed memory
s = FMU2Slave(guid=md.guid, unzipDirectory=d, modelIdentifier="riser", instanceName="later")
s.instantiate()
try:
    s.setReal([987654321], [1.0])
except Exception as e:
    print("refused:", e)
s.freeInstance()
print("alive", len(msgs))
