#include "io/log_writer.h"

#include <filesystem>
#include <sstream>

#include "io/csv_writer.h"
#include "io/log_tables.h"
#include "io/text_file.h"
#include "io/yaml_config.h"

namespace slipgraph {

void WriteDriveLog(const DriveLog& log, const std::string& directory) {
  namespace fs = std::filesystem;
  fs::create_directories(directory);
  {
    std::ostringstream yaml;
    WriteVehicleYaml(log.vehicle, yaml);
    WriteTextFile((fs::path(directory) / "vehicle.yaml").string(), yaml.str());
  }
  for (const std::string& file : LogTableFiles(log)) {
    const LogTable table = StreamTable(log, file);
    std::vector<std::string> header;
    for (const LogColumn& column : table.columns) header.push_back(column.name);
    CsvWriter writer((fs::path(directory) / file).string(), header);
    for (size_t row = 0; row < table.rows(); ++row) {
      for (const LogColumn& column : table.columns) {
        if (column.is_text) {
          writer << column.texts[row];
        } else {
          writer << column.numbers[row];
        }
      }
      writer.EndRow();
    }
    writer.Close();
  }
}

}  // namespace slipgraph
