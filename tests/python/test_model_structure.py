"""The FMU's <ModelStructure> tells the truth (issue 52; build.rs, FMI 2.0.5 §2.2.8).

At a communication point no output depends on an input (an output changes only
in fmi2DoStep): every <Outputs> entry has dependencies="" (left out, it would
mean "on every known": a direct feedthrough, so an algebraic loop wherever an
output is fed back). In Initialization Mode the outputs (the static state) do
depend on the inputs set then and on the parameters: <InitialUnknowns> lists
those knowns. Checked on the XML, by fmu-manipulation-toolbox's checkers and by
libcosim running riser with its top force fed back to its own heave."""

import re
import zipfile
import xml.etree.ElementTree as ET

from fmpy import read_model_description

def model_description(fmu):
    with zipfile.ZipFile(fmu) as z:
        return ET.fromstring(z.read("modelDescription.xml"))


def with_model_description(fmu, out, edit):
    """A copy of `fmu` at `out` whose modelDescription.xml is `edit(text)`."""
    with zipfile.ZipFile(fmu) as src, zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as dst:
        for item in src.infolist():
            data = src.read(item)
            if item.filename == "modelDescription.xml":
                data = edit(data.decode()).encode()
            dst.writestr(item, data)
    return str(out)


def old_declaration(text):
    """The declaration before issue 52: no dependencies attribute ("depends on every known")."""
    return re.sub(r' dependencies="[^"]*"', "", text)


def algebraic_loop(root, connections, section="Outputs"):
    """A cycle that a master ordering its FMUs by <ModelStructure> finds, or None: an edge
    from each connected output to its input, and inside the FMU from each input to the
    outputs of `section` that depend on it (every input where `dependencies` is absent)."""
    variables = root.find("ModelVariables").findall("ScalarVariable")
    names = [v.get("name") for v in variables]
    inputs = [n for n, v in zip(names, variables) if v.get("causality") == "input"]
    graph = {}
    for out, inp in connections:
        graph.setdefault(out, set()).add(inp)
    for u in root.find("ModelStructure").find(section):
        deps = u.get("dependencies")
        for known in inputs if deps is None else [names[int(k) - 1] for k in deps.split()]:
            if known in inputs:
                graph.setdefault(known, set()).add(names[int(u.get("index")) - 1])
    path, done = [], set()

    def visit(node):
        if node in path:
            return path[path.index(node):] + [node]
        if node in done:
            return None
        path.append(node)
        for nxt in sorted(graph.get(node, ())):
            if cycle := visit(nxt):
                return cycle
        path.pop()
        done.add(node)
        return None

    return next((c for c in map(visit, sorted(graph)) if c), None)


def test_outputs_have_no_feedthrough_and_initial_unknowns_list_the_initialisation_knowns(fmu_path):
    root = model_description(fmu_path)
    variables = root.find("ModelVariables").findall("ScalarVariable")
    outputs = [i + 1 for i, v in enumerate(variables) if v.get("causality") == "output"]
    inputs = {i + 1 for i, v in enumerate(variables) if v.get("causality") == "input"}
    exact = {i + 1 for i, v in enumerate(variables) if v.get("initial") == "exact"}
    structure = root.find("ModelStructure")
    out = structure.find("Outputs").findall("Unknown")
    assert [int(u.get("index")) for u in out] == outputs
    for u in out:
        assert u.get("dependencies") == "", u.attrib  # present and empty: on none of the knowns
    init = structure.find("InitialUnknowns").findall("Unknown")
    # the initial unknowns: the outputs and the calculated parameters (the numerics run, FMI 2.0.5
    # §2.2.8), in index order
    calculated = [i + 1 for i, v in enumerate(variables) if v.get("causality") == "calculatedParameter"]
    assert calculated and [int(u.get("index")) for u in init] == sorted(outputs + calculated)
    for u in init:
        deps = [int(k) for k in u.get("dependencies").split()]
        assert deps == sorted(deps)
        # the knowns of Initialization Mode: the inputs and the variables with initial="exact"
        assert set(deps) == inputs | exact, u.get("index")
    # fmpy reads the same: every output on no input
    md = read_model_description(fmu_path)
    assert all(u.dependencies == [] for u in md.outputs)
    assert all(len(u.dependencies) == len(inputs | exact) for u in md.initialUnknowns)


def test_the_fmu_behaves_as_declared(fmu_path, unzipped):
    # what the declaration says, asked of the binary: in Initialization Mode the outputs follow
    # the inputs set then; in Step Mode setting every input changes no output before fmi2DoStep
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    inputs = [v.valueReference for v in md.modelVariables if v.causality == "input"]
    s = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier="riser", instanceName="structure")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.setInteger([vr["n_elements"]], [10])
    static = s.getReal([vr["top_force_z"]])[0]
    stiffness = s.getDirectionalDerivative([vr["top_force_z"]], [vr["heave"]], [1.0])[0]
    s.setReal([vr["heave"]], [1e-3])
    # the statics solved again with the hang-off moved 1 mm (docs/theory.md §7.7): the change is the
    # line's stiffness times the move (the derivative at the static state; 1 % for the curvature)
    moved = s.getReal([vr["top_force_z"]])[0] - static
    assert moved != 0.0 and abs(moved - 1e-3 * stiffness) <= 1e-2 * abs(moved), (moved, stiffness)
    s.setReal([vr["heave"]], [0.0])
    s.exitInitializationMode()
    s.doStep(0.0, 0.05)
    before = s.getReal(outputs)
    s.setReal(inputs, [0.01] * len(inputs))
    assert s.getReal(outputs) == before  # no feedthrough
    s.doStep(0.05, 0.05)
    assert s.getReal([vr["top_force_z"]]) != [before[outputs.index(vr["top_force_z"])]]
    s.terminate()
    s.freeInstance()


def test_a_loop_checking_master_finds_no_algebraic_loop_in_riser_fed_back_on_itself(fmu_path):
    # riser's top force fed back to its own heave (a vessel that sinks under the riser's pull)
    loop = [("top_force_z", "heave")]
    root = model_description(fmu_path)
    assert algebraic_loop(root, loop) is None
    # the declaration before issue 52 made it one: heave -> top_force_z -> heave
    old = ET.fromstring(old_declaration(ET.tostring(root, encoding="unicode")))
    assert set(algebraic_loop(old, loop)) == {"heave", "top_force_z"}
    # during initialisation the loop is real (the static state hangs from the heave set
    # then) and declared: libcosim's initialisation iterates it (the test below)
    assert set(algebraic_loop(root, loop, "InitialUnknowns")) == {"heave", "top_force_z"}


def test_fmu_manipulation_toolbox_checks_the_model_structure_clean(fmu_path, tmp_path):
    from fmu_manipulation_toolbox.checker import OperationGenericCheck, OperationSemanticCheck
    from fmu_manipulation_toolbox.operations import FMU

    def check(path):
        generic, semantic = OperationGenericCheck(), OperationSemanticCheck()
        with FMU(path) as fmu:
            fmu.apply_operation(generic)
            fmu.apply_operation(semantic)
        return generic.compliant_with_version, semantic.errors

    # the XSD of FMI 2.0 and the rules it cannot express, <ModelStructure>'s among them
    assert check(fmu_path) == ("2.0", [])
    # it does read the dependencies: a dependenciesKind longer than them is reported
    bad = with_model_description(fmu_path, tmp_path / "bad.fmu", lambda t: t.replace(
        'dependencies=""', 'dependencies="" dependenciesKind="dependent"', 1))
    version, errors = check(bad)
    assert len(errors) == 1 and "dependenciesKind" in errors[0], errors


def test_libcosim_runs_riser_with_its_top_force_fed_back_to_its_heave(fmu_path, tmp_path):
    # heave = top_force_z / K, a support of stiffness K sinking under the riser's pull (K stiff,
    # 1e10 N/m, as a massless spring must be against the line's axial stiffness, README "4.2 Hz");
    # libcosim (fixed step, Jacobi) takes the loop as any connection: it reads no <ModelStructure>
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.ERROR)  # riser warns that the heave is not 0 at the start
    k = 1e10
    (tmp_path / "OspSystemStructure.xml").write_text(f"""<?xml version="1.0" encoding="utf-8"?>
<OspSystemStructure xmlns="http://opensimulationplatform.com/MSMI/OSPSystemStructure" version="0.1">
  <StartTime>0.0</StartTime>
  <BaseStepSize>0.05</BaseStepSize>
  <Algorithm>fixedStep</Algorithm>
  <Simulators>
    <Simulator name="riser" source="{fmu_path}" stepSize="0.05">
      <InitialValues>
        <InitialValue variable="n_elements"><Integer value="10"/></InitialValue>
      </InitialValues>
    </Simulator>
  </Simulators>
  <Functions>
    <LinearTransformation name="support" factor="{1 / k}" offset="0"/>
  </Functions>
  <Connections>
    <SignalConnection>
      <Variable simulator="riser" name="top_force_z"/>
      <Signal function="support" name="in"/>
    </SignalConnection>
    <SignalConnection>
      <Signal function="support" name="out"/>
      <Variable simulator="riser" name="heave"/>
    </SignalConnection>
  </Connections>
</OspSystemStructure>
""")
    ex = CosimExecution.from_osp_config_file(osp_path=str(tmp_path / "OspSystemStructure.xml"))
    obs = CosimObserver.create_last_value()
    ex.add_observer(observer=obs)
    idx = ex.slave_index_from_instance_name("riser")
    ref = {v.name.decode(): v.reference for v in ex.slave_variables(idx)}
    refs = [ref["top_force_z"], ref["heave"]]
    fz, heave = [], []
    for _ in range(20):  # 1 s
        assert ex.step()
        f, h = obs.last_real_values(slave_index=idx, variable_references=refs)
        fz.append(f)
        heave.append(h)
    print(f"after 1 s: top_force_z {fz[-1]:.6e} N, heave {heave[-1]:.6e} m")
    # the loop is closed, one communication step late: each step's heave is the force the
    # step before gave, the output a function of the inputs of earlier steps only
    assert all(f < -1e5 for f in fz)
    for i in range(1, 20):
        assert abs(heave[i] - fz[i - 1] / k) <= 1e-12 * abs(fz[i - 1] / k), i
