#include "three_reader.h"

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#ifndef WIRERIG_SOURCE_DIR
#error "three_reader.cpp needs WIRERIG_SOURCE_DIR (set by CMake)"
#endif

namespace wirerig::testing {
namespace {

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `command`, returns its standard output and sets *status (-1 if it did not exit).
std::string Run(const std::string& command, int* status) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    *status = -1;
    return out;
  }
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
  const int result = ::pclose(pipe);
  *status = WIFEXITED(result) ? WEXITSTATUS(result) : -1;
  return out;
}

ThreeMesh ParseMesh(const nlohmann::json& mesh) {
  ThreeMesh out;
  out.name = mesh.at("name").get<std::string>();
  out.skinned = mesh.at("skinned").get<bool>();
  out.morph_targets = mesh.at("morph_targets").get<std::size_t>();
  out.primitives = mesh.at("primitives").get<std::size_t>();
  out.primitive_spread = mesh.at("primitive_spread").get<double>();
  const auto vertices = mesh.at("vertex_count").get<std::size_t>();
  for (const nlohmann::json& at_time : mesh.at("positions")) {
    const auto xyz = at_time.get<std::vector<double>>();
    if (xyz.size() != 3 * vertices) throw std::runtime_error("positions of the wrong size");
    std::vector<Vec3>& positions = out.positions.emplace_back();
    for (std::size_t v = 0; v < vertices; ++v) {
      positions.emplace_back(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    }
  }
  return out;
}

}  // namespace

ThreePlayback PlayWithThree(const std::filesystem::path& file, const std::vector<double>& times) {
  ThreePlayback playback;
  int status = -1;
  Run("node --version", &status);
  if (status != 0) {
    playback.error = "node is not installed: run scripts/setup.sh (the three.js test cannot skip)";
    return playback;
  }
  std::string list;
  for (double t : times) {
    char number[32];
    std::snprintf(number, sizeof number, "%.17g", t);
    list.append(list.empty() ? "" : ",").append(number);
  }
  const std::filesystem::path errors = file.string() + ".three-stderr.txt";
  std::ostringstream command;
  command << "node '" << WIRERIG_SOURCE_DIR << "/scripts/three_skinned_positions.mjs' '"
          << file.string() << "' --times " << list << " 2> '" << errors.string() << "'";
  const std::string out = Run(command.str(), &status);
  const std::string stderr_text = ReadText(errors);
  std::filesystem::remove(errors);
  if (status != 0) {
    playback.error = "three_skinned_positions.mjs exited " + std::to_string(status) + ": " +
                     stderr_text + " (run scripts/setup.sh to install three.js)";
    return playback;
  }
  try {
    const nlohmann::json document = nlohmann::json::parse(out);
    playback.revision = document.at("three").get<std::string>();
    if (!document.at("animation").is_null()) {
      playback.animation = document.at("animation").at("name").get<std::string>();
    }
    for (const nlohmann::json& mesh : document.at("meshes")) {
      playback.meshes.push_back(ParseMesh(mesh));
      if (playback.meshes.back().positions.size() != times.size()) {
        throw std::runtime_error("not one set of positions per time");
      }
    }
  } catch (const std::exception& error) {
    playback.error = std::string("cannot parse three_skinned_positions.mjs's output: ") +
                     error.what() + "; stderr: " + stderr_text;
  }
  return playback;
}

}  // namespace wirerig::testing
