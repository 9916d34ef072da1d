// Import of MATLAB v7.3 recordings (HDF5 inside) into the drive-log format, driven by a mapping
// file (YAML) that names the variables of each stream and states the source's conventions:
//
//   format: matlab_v73
//   imu:    {t: tTimu, ax: Ax, ay: Ay, az: Az, gx: Gx, gy: Gy, gz: Gz, frame: z_down}
//   wheels: {t: tTodom, left: [frontLeftVel, rearLeftVel], right: [frontRightVel, rearRightVel],
//            left_sign: -1, right_sign: 1}
//   gps:    {t: tTGPS, enu: ENUGPS, sd_xy: 2.6, sd_v: 0.1}
//
// `frame: z_down` rotates the IMU by 180 deg about x (y and z change sign) into REP-103; wheel
// speeds of a side are averaged and multiplied by the side's sign (positive = driving forward);
// GNSS velocity, when the source has only positions, is their central difference. Times are
// shifted so the earliest stamp of any stream is 0. Every choice is written into the imported
// log's vehicle.yaml comment-free data and reported by `import`.
#pragma once

#include <string>
#include <vector>

#include "io/drive_log.h"
#include "io/import_report.h"

namespace slipgraph {

// One topic or variable of a recording (`import --list`): its name, type (a ROS message type, or
// an HDF5 dataset's dimensions), how many messages or values, and, for a topic, its rate.
struct SourceEntry {
  std::string name, type;
  long count = 0;
  double rate_hz = 0.0;  // 0: not a time series (a MATLAB variable)
};

// The root variables of a MATLAB v7.3 / HDF5 file. Throws InputError when it is not HDF5.
std::vector<SourceEntry> ListMatlab(const std::string& source);

// Throws InputError naming the mapping file and key, or the source and variable.
DriveLog ImportMatlab(const std::string& source, const std::string& mapping_path,
                      const Vehicle& vehicle, ImportReport* report);

}  // namespace slipgraph
