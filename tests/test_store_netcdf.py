"""A result file written through h5py in one pass is the netCDF4 file xarray's h5netcdf
engine writes: the same HDF5 objects, dimension scales and attributes, read back the same by
xarray (both engines) and by netCDF-C itself (netCDF4-python)."""
import json

import h5py
import netCDF4
import numpy as np
import pytest
import xarray as xr

from fickcam.results import ncwrite
from fickcam.results.store import open_result, save

#: what the two writers may differ in: the library named in _NCProperties
WRITER_ATTRIBUTE = "_NCProperties"


def dataset() -> xr.Dataset:
    """Every kind of variable a result holds: float, int and bool data, text coordinates, a
    coordinate off its dimension (ageing_time), a dimension without a coordinate (point),
    scalars, NaN, and attributes of each netCDF type."""
    rng = np.random.default_rng(3)
    ds = xr.Dataset(
        {"moisture_content": (("time", "part"), rng.random((4, 2)), {"units": "%", "long_name": "m"}),
         "lift": ("time", np.array([1.0, np.nan, 3.0, 4.0]), {"units": "m"}),
         "profile_x": (("time", "point"), rng.random((4, 7)), {"units": "m"}),
         "within_wet_tg": (("time", "part"), np.array([[True, False]] * 4)),
         "cycles": ("part", np.array([3, 4], dtype=np.int64), {"scale": 2.5, "tags": [1, 2]}),
         "lift_design": ((), 0.5, {"units": "m"})},
        coords={"time": ("time", [0.0, 1.0, 2.0, 3.0], {"units": "d"}),
                "part": ("part", ["cam", "follower"], {"long_name": "part"}),
                "ageing_time": ("time", [0.0, 86400.0, 2 * 86400.0, 3 * 86400.0], {"units": "s"})},
        attrs={"title": "a result", "notices": ["one", "two"], "wall_time": 1.5, "flag": True})
    return ds


def via_xarray(ds, path, monkeypatch, compress=False):
    """``save`` through xarray's h5netcdf engine (the writer before fickcam.results.ncwrite)."""
    with monkeypatch.context() as patched:
        patched.setattr(ncwrite, "writable", lambda ds: False)
        save(ds, path, compress=compress)


def written_by(path) -> str:
    """The library _NCProperties names after the format version."""
    with h5py.File(path, "r") as file:
        return file.attrs[WRITER_ATTRIBUTE].decode().split(",")[1].split("=")[0]


def layout(path) -> dict:
    """Every object of an HDF5 file: type, shape, filters, fill, link and attribute creation
    order, and each attribute's type and value (dimension lists by the names they point
    at), the attributes in a stable order."""
    objects = {}
    with h5py.File(path, "r") as file:
        def attribute(obj, key):
            value = obj.attrs[key]
            if key == "DIMENSION_LIST":
                return [[file[ref].name for ref in refs] for refs in value]
            if key == "REFERENCE_LIST":
                return sorted((file[ref].name, int(axis)) for ref, axis in value)
            return repr(value)

        def described(obj):
            attributes = {key: (obj.attrs.get_id(key).dtype.str, obj.attrs.get_id(key).shape,
                                attribute(obj, key)) for key in obj.attrs if key != WRITER_ATTRIBUTE}
            return {"attributes": dict(sorted(attributes.items())),
                    "attribute order": obj.id.get_create_plist().get_attr_creation_order()}

        objects["/"] = {**described(file), "links": list(file),
                        "link order": file.id.get_create_plist().get_link_creation_order()}
        for name, obj in file.items():
            objects[name] = {**described(obj), "dtype": obj.dtype.str, "shape": obj.shape,
                             "maxshape": obj.maxshape, "chunks": obj.chunks,
                             "filters": (obj.compression, obj.compression_opts, obj.shuffle,
                                         obj.fletcher32),
                             "fill": repr(obj.fillvalue)}
    return objects


@pytest.mark.parametrize("compress, chunked", [(False, False), (True, False), (True, True)])
def test_the_file_is_the_one_h5netcdf_writes(tmp_path, monkeypatch, compress, chunked):
    ds = dataset()
    if chunked:  # chunks and a checksum asked for in a variable's encoding
        ds.profile_x.encoding.update(chunksizes=(2, 7), fletcher32=True)
    save(ds, tmp_path / "h5py.h5", compress=compress)
    via_xarray(ds, tmp_path / "xarray.h5", monkeypatch, compress)
    assert written_by(tmp_path / "h5py.h5") == "h5py"
    assert written_by(tmp_path / "xarray.h5") == "h5netcdf"
    ours, theirs = layout(tmp_path / "h5py.h5"), layout(tmp_path / "xarray.h5")
    assert list(ours) == list(theirs)
    for name in theirs:
        assert ours[name] == theirs[name], name


def test_xarray_reads_the_same_dataset_attributes_in_order(tmp_path, monkeypatch):
    ds = dataset()
    save(ds, tmp_path / "h5py.h5")
    via_xarray(ds, tmp_path / "xarray.h5", monkeypatch)
    for engine in ("h5netcdf", "netcdf4"):
        with (xr.open_dataset(tmp_path / "h5py.h5", engine=engine) as ours,
              xr.open_dataset(tmp_path / "xarray.h5", engine=engine) as theirs):
            xr.testing.assert_identical(ours, theirs)
            assert list(ours.variables) == list(theirs.variables)
            for name in theirs.variables:
                assert list(ours[name].attrs) == list(theirs[name].attrs), name
    read = open_result(tmp_path / "h5py.h5")
    assert read.attrs["notices"] == ["one", "two"]
    assert read.within_wet_tg.dtype == bool and read.part.values.tolist() == ["cam", "follower"]


def test_netcdf_c_reads_dimensions_variables_and_attributes(tmp_path):
    ds = dataset()
    save(ds, tmp_path / "r.nc")
    with netCDF4.Dataset(tmp_path / "r.nc") as nc:
        assert nc.data_model == "NETCDF4"
        assert {name: len(dim) for name, dim in nc.dimensions.items()} == {
            "time": 4, "part": 2, "point": 7}
        assert nc["profile_x"].dimensions == ("time", "point")
        assert nc["lift_design"].dimensions == ()
        assert nc["moisture_content"].getncattr("units") == "%"
        assert nc["lift"].getncattr("coordinates") == "ageing_time"
        np.testing.assert_array_equal(nc["lift"][:].filled(np.nan), ds.lift.values)
        assert list(nc["part"][:]) == ["cam", "follower"]
        assert json.loads(nc.getncattr("notices")) == ["one", "two"]


@pytest.mark.parametrize("change", ["name of a dimension off its axis", "other filter",
                                    "fill value"])
def test_what_it_does_not_write_the_same_goes_through_xarray(change, tmp_path):
    ds = dataset()
    if change == "name of a dimension off its axis":
        ds = ds.assign(point=(("time",), np.arange(4.0)))
    elif change == "other filter":
        ds.lift.encoding["zstd"] = True
    else:
        ds.cycles.encoding["_FillValue"] = -1
    prepared = ds.copy(deep=False)
    for variable in prepared.variables.values():
        if variable.dtype.kind == "f":
            variable.encoding.setdefault("_FillValue", None)  # as save sets it
    assert not ncwrite.writable(prepared)
    if change != "other filter":  # zstd needs a filter plugin
        save(ds, tmp_path / "r.h5")
        assert written_by(tmp_path / "r.h5") == "h5netcdf"
        xr.testing.assert_equal(open_result(tmp_path / "r.h5").drop_vars("ageing_time"),
                                ds.drop_vars("ageing_time"))
