#include "colag/sim/world/pcd_loader.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace colag::sim {

namespace {
constexpr double kMaxCoordinate_m = 1e6;
}  // namespace

bool load_pcd(const std::string& path, std::vector<Vec3>& points, std::string& error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = "cannot open " + path;
    return false;
  }
  std::ostringstream all;
  all << in.rdbuf();
  if (!parse_pcd(all.str(), points, error)) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

bool parse_pcd(const std::string& bytes, std::vector<Vec3>& points, std::string& error) {
  std::vector<std::string> fields, types;
  std::vector<int> sizes, counts;
  long long declared = -1, width = -1, height = 1;
  std::string data;
  std::size_t pos = 0;
  int line_no = 0;
  while (data.empty()) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) {
      error = "header ends without a DATA line";
      return false;
    }
    std::string line = bytes.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    const auto read_list = [&](auto& list) {
      typename std::decay_t<decltype(list)>::value_type v;
      while (ls >> v)
        list.push_back(v);
    };
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS") {
      read_list(fields);
    } else if (key == "SIZE") {
      read_list(sizes);
    } else if (key == "TYPE") {
      read_list(types);
    } else if (key == "COUNT") {
      read_list(counts);
    } else if (key == "WIDTH") {
      ls >> width;
    } else if (key == "HEIGHT") {
      ls >> height;
    } else if (key == "POINTS") {
      ls >> declared;
    } else if (key == "DATA") {
      ls >> data;
    } else {
      error = "line " + std::to_string(line_no) + ": unknown header key '" + key + "'";
      return false;
    }
  }
  if (counts.empty()) counts.assign(fields.size(), 1);
  if (fields.empty() || sizes.size() != fields.size() || types.size() != fields.size() ||
      counts.size() != fields.size()) {
    error = "FIELDS, SIZE, TYPE and COUNT must list the same number of entries";
    return false;
  }
  constexpr long long kMaxPoints = 100'000'000;
  if (declared < 0 && width >= 0 && width <= kMaxPoints && height >= 0 && height <= kMaxPoints)
    declared = width * height;
  if (declared < 0 || declared > kMaxPoints) {
    error = "missing or absurd POINTS/WIDTH";
    return false;
  }
  for (std::size_t f = 0; f < fields.size(); ++f) {
    if (sizes[f] != 1 && sizes[f] != 2 && sizes[f] != 4 && sizes[f] != 8) {
      error = "field " + fields[f] + ": SIZE must be 1, 2, 4 or 8";
      return false;
    }
    if (counts[f] < 1 || counts[f] > 4096) {
      error = "field " + fields[f] + ": COUNT must be 1..4096";
      return false;
    }
  }
  // Where x, y, z are in a point record.
  int index[3] = {-1, -1, -1};
  std::size_t offset[3] = {0, 0, 0}, record = 0, column = 0;
  int column_of[3] = {0, 0, 0};
  for (std::size_t f = 0; f < fields.size(); ++f) {
    for (int a = 0; a < 3; ++a) {
      if (fields[f] == std::string(1, static_cast<char>('x' + a))) {
        if (types[f] != "F" || (sizes[f] != 4 && sizes[f] != 8)) {
          error = "field " + fields[f] + " must be TYPE F with SIZE 4 or 8";
          return false;
        }
        index[a] = static_cast<int>(f);
        offset[a] = record;
        column_of[a] = static_cast<int>(column);
      }
    }
    record += static_cast<std::size_t>(sizes[f]) * static_cast<std::size_t>(counts[f]);
    column += static_cast<std::size_t>(counts[f]);
  }
  if (index[0] < 0 || index[1] < 0 || index[2] < 0) {
    error = "the cloud needs x, y and z fields";
    return false;
  }
  points.clear();
  // Never trust the header with memory: a point takes at least 6 bytes of text ("0 0 0\n") or
  // one record of binary data.
  const std::size_t body_bytes = bytes.size() - pos;
  points.reserve(std::min(static_cast<std::size_t>(declared), body_bytes / 6));
  if (data == "ascii") {
    std::istringstream body(bytes.substr(pos));
    std::string line;
    while (static_cast<long long>(points.size()) < declared && std::getline(body, line)) {
      if (line.empty() || line == "\r") continue;
      std::istringstream ls(line);
      std::vector<double> values;
      double v = 0.0;
      while (ls >> v)
        values.push_back(v);
      if (!ls.eof() || values.size() != column) {
        error = "point " + std::to_string(points.size() + 1) + ": expected " +
                std::to_string(column) + " numbers";
        return false;
      }
      points.emplace_back(values[static_cast<std::size_t>(column_of[0])],
                          values[static_cast<std::size_t>(column_of[1])],
                          values[static_cast<std::size_t>(column_of[2])]);
    }
  } else if (data == "binary") {
    if (body_bytes / record < static_cast<std::size_t>(declared)) {
      error = "binary data truncated: " + std::to_string(declared) + " points of " +
              std::to_string(record) + " bytes declared";
      return false;
    }
    for (long long i = 0; i < declared; ++i) {
      const char* p = bytes.data() + pos + static_cast<std::size_t>(i) * record;
      Vec3 q;
      for (int a = 0; a < 3; ++a) {
        if (sizes[static_cast<std::size_t>(index[a])] == 4) {
          float f = 0.0F;
          std::memcpy(&f, p + offset[a], 4);
          q[a] = f;
        } else {
          std::memcpy(&q[a], p + offset[a], 8);
        }
      }
      points.push_back(q);
    }
  } else {
    error = "DATA " + data + " is not supported (use ascii or binary)";
    return false;
  }
  if (static_cast<long long>(points.size()) != declared) {
    error = "the file has " + std::to_string(points.size()) + " points, the header says " +
            std::to_string(declared);
    return false;
  }
  for (const Vec3& q : points) {
    if (!all_finite(q)) {
      error = "a point is not finite";
      return false;
    }
    if (q.cwiseAbs().maxCoeff() > kMaxCoordinate_m) {
      error = "a point is more than 1000 km from the origin (units not metres?)";
      return false;
    }
  }
  return true;
}

}  // namespace colag::sim
