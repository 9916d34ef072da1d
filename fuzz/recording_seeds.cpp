// Writes the seeds of recording_fuzzer: the tiny MATLAB file and the tiny ROS bag, each behind
// the byte that picks it. Usage: recording_seeds DIRECTORY
#include <cstdio>
#include <fstream>
#include <string>

#include "io/text_file.h"
#include "tests/tiny_recordings.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: recording_seeds DIRECTORY\n");
    return 2;
  }
  const std::string dir = argv[1];
  const std::string mat = slipgraph::testing::WriteTinyMat(dir, "tiny.mat");
  const std::string bag = slipgraph::testing::WriteTinyBag(dir, "tiny.bag");
  std::ofstream(dir + "/matlab", std::ios::binary) << '\x00' << slipgraph::ReadTextFile(mat);
  std::ofstream(dir + "/bag", std::ios::binary) << '\x01' << slipgraph::ReadTextFile(bag);
  std::remove(mat.c_str());
  std::remove(bag.c_str());
  return 0;
}
