"""The nylon cam scene the drawn-cam tests vary (a shape key added: ``drawing``, ``outline``)."""
import yaml

from fickcam.cli.main import main

NYLON_CAM = {
    "name": "drawn-cam", "materials": {"nylon": {"plastic": "nylon"}},
    "cam": {"material": "nylon", "thickness": "10 mm", "speed": "300 rpm",
            "follower": {"kind": "roller", "roller_radius": "10 mm", "mass": "0.737 kg",
                         "spring_rate": "660.02 N/m"}},
    "environment": {"history": [{"duration": "60 d", "temperature": "40 degC",
                                 "relative_humidity": "90 %"}]},
    "outputs": {"ageing_times": {"every": "20 d"}, "angle_step": "2 deg"}}


def scene(folder, name, **cam):
    """The scene file ``folder/name.yaml``: the nylon cam with ``cam`` keys added."""
    data = yaml.safe_load(yaml.safe_dump(NYLON_CAM))
    data["cam"].update(cam)
    path = folder / f"{name}.yaml"
    path.write_text(yaml.safe_dump(data, default_flow_style=None))
    return path


def refused(capsys, path) -> str:
    """The one line `fickcam check` refuses the scene with (exit status 2)."""
    code = main(["check", str(path)])
    err = capsys.readouterr().err.strip()
    assert code == 2, err
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    return err
