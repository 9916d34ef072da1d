// Reading numeric variables from MATLAB v7.3 files (HDF5 inside) with Debian's HDF5 library.
// MATLAB stores an R x C matrix column-major, which HDF5 presents as C x R: a 1 x N MATLAB row
// vector and an N x 1 column both come back as N values; an N x 3 table of rows comes back with
// `columns` = 3 when HDF5 reports (N, 3).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace slipgraph {

struct Hdf5Matrix {
  size_t rows = 0, columns = 0;  // as HDF5 reports the dataset's two dimensions
  std::vector<double> values;    // row-major, converted to double
  double At(size_t row, size_t column) const { return values[row * columns + column]; }
  // The values as one vector when the dataset is 1 x N or N x 1; throws otherwise.
  std::vector<double> Vector(const std::string& name) const;
};

// The root datasets of an HDF5 file: name and dimensions ("N x M"). Throws InputError when the
// file is not HDF5.
std::vector<std::pair<std::string, std::vector<unsigned long long>>> ListHdf5Datasets(
    const std::string& path);

// The most values one variable may hold (512 MB as doubles: 93 hours of a 200 Hz IMU channel).
inline constexpr unsigned long long kMaxHdf5Values = 1ULL << 26;

// Throws InputError naming the file and the variable when it is missing, not numeric (or of a
// number type wider than 8 bytes), or holds more than kMaxHdf5Values: a corrupted file's
// dimensions are not allocated as read.
Hdf5Matrix ReadHdf5Matrix(const std::string& path, const std::string& name);

}  // namespace slipgraph
