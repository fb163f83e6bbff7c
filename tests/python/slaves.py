"""The FMU instantiated and through initialization, as the tests drive it
through fmpy's FMU2Slave: one place for the call sequence."""
from fmpy import read_model_description
from fmpy.fmi2 import FMU2Slave


def started_slave(fmu_path, unzipped, name="riser", scene=None, strings=None, reals=None, integers=None):
    """An instance after fmi2ExitInitializationMode, with `scene`, the given
    string, real and integer parameters set in initialization mode. Returns
    the slave and the value references by name."""
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName=name)
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    if scene is not None:
        s.setString([vr["scene"]], [scene])
    for k, v in (strings or {}).items():
        s.setString([vr[k]], [v])
    for k, v in (reals or {}).items():
        s.setReal([vr[k]], [v])
    for k, v in (integers or {}).items():
        s.setInteger([vr[k]], [v])
    s.exitInitializationMode()
    return s, vr
