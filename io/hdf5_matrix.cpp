#include "io/hdf5_matrix.h"

#include <hdf5.h>

#include "io/input_error.h"

namespace slipgraph {
namespace {

// Closes an HDF5 handle when it leaves scope.
struct Handle {
  hid_t id;
  herr_t (*close)(hid_t);
  ~Handle() {
    if (id >= 0) close(id);
  }
};

}  // namespace

std::vector<double> Hdf5Matrix::Vector(const std::string& name) const {
  if (rows != 1 && columns != 1) {
    throw InputError(name, 0, "", "",
                     "expected a vector, found a " + std::to_string(rows) + " x " +
                         std::to_string(columns) + " matrix");
  }
  return values;
}

std::vector<std::pair<std::string, std::vector<unsigned long long>>> ListHdf5Datasets(
    const std::string& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const Handle file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) {
    throw InputError(path, 0, "", "", "cannot open as HDF5 (a MATLAB v7.3 .mat file?)");
  }
  H5G_info_t info;
  if (H5Gget_info(file.id, &info) < 0) throw InputError(path, 0, "", "", "cannot list its root");
  std::vector<std::pair<std::string, std::vector<unsigned long long>>> out;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size =
        H5Lget_name_by_idx(file.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size <= 0) continue;
    std::string name(static_cast<size_t>(size), '\0');
    H5Lget_name_by_idx(file.id, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), size + 1,
                       H5P_DEFAULT);
    {
      const Handle object{H5Oopen(file.id, name.c_str(), H5P_DEFAULT), H5Oclose};
      if (object.id < 0 || H5Iget_type(object.id) != H5I_DATASET) {
        continue;  // groups (MATLAB's #refs#, structs) are not variables a mapping names
      }
    }
    const Handle dataset{H5Dopen2(file.id, name.c_str(), H5P_DEFAULT), H5Dclose};
    const Handle space{H5Dget_space(dataset.id), H5Sclose};
    const int rank = H5Sget_simple_extent_ndims(space.id);
    std::vector<hsize_t> dims(rank > 0 ? rank : 0);
    if (rank > 0) H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
    out.push_back({name, std::vector<unsigned long long>(dims.begin(), dims.end())});
  }
  return out;
}

Hdf5Matrix ReadHdf5Matrix(const std::string& path, const std::string& name) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // errors become exceptions here, not prints
  const Handle file{H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  if (file.id < 0) {
    throw InputError(path, 0, "", "", "cannot open as HDF5 (a MATLAB v7.3 .mat file?)");
  }
  if (H5Lexists(file.id, name.c_str(), H5P_DEFAULT) <= 0) {
    throw InputError(path, 0, name, "", "no variable named '" + name + "'");
  }
  const Handle dataset{H5Dopen2(file.id, name.c_str(), H5P_DEFAULT), H5Dclose};
  const Handle space{H5Dget_space(dataset.id), H5Sclose};
  const Handle type{H5Dget_type(dataset.id), H5Tclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  const H5T_class_t type_class = H5Tget_class(type.id);
  if (dataset.id < 0 || rank < 1 || rank > 2 ||
      (type_class != H5T_FLOAT && type_class != H5T_INTEGER) || H5Tget_size(type.id) > 8) {
    throw InputError(path, 0, name, "", "not a numeric vector or matrix");
  }
  hsize_t dims[2] = {1, 1};
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  // The file states the size: a corrupted one must not make us allocate what it claims.
  const hsize_t rows = rank == 2 ? dims[0] : 1, columns = rank == 2 ? dims[1] : dims[0];
  if (columns != 0 && rows > kMaxHdf5Values / columns) {
    throw InputError(path, 0, name, "",
                     std::to_string(rows) + " x " + std::to_string(columns) +
                         " values: more than this reader takes (" + std::to_string(kMaxHdf5Values) +
                         "; a corrupted file?)");
  }
  Hdf5Matrix m;
  m.rows = rows;
  m.columns = columns;
  m.values.resize(m.rows * m.columns);
  if (H5Dread(dataset.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, m.values.data()) < 0) {
    throw InputError(path, 0, name, "", "could not be read as numbers");
  }
  return m;
}

}  // namespace slipgraph
