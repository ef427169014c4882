// Tribos_Summary.hpp: the run summary, one flat-ish JSON object that scripts
// read (keys in insertion order; values are numbers, strings, booleans, arrays
// of numbers or nested objects).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Tribos {
namespace IO {

class Summary {
 public:
  Summary& set(const std::string& key, double v);
  Summary& set(const std::string& key, long long v);
  Summary& set(const std::string& key, int v) { return set(key, static_cast<long long>(v)); }
  Summary& set(const std::string& key, bool v);
  Summary& set(const std::string& key, const std::string& v);
  Summary& set(const std::string& key, const char* v) { return set(key, std::string(v)); }
  Summary& set(const std::string& key, const std::vector<double>& v);
  Summary& set(const std::string& key, const Summary& object);
  Summary& set(const std::string& key, const std::vector<Summary>& objects);  // an array of objects
  std::string toJson(int indent = 0) const;
  // The same JSON on one line (a row of a JSON Lines table).
  std::string toJsonLine() const;
  bool has(const std::string& key) const;

  // A summary read back (a restarted run continues its steps' rows): the
  // members of the JSON object `json`, each value kept as its JSON text, so
  // that a member set again writes the text it was read from. Throws
  // Tribos::Error naming the offset of what is not JSON.
  static Summary fromJson(const std::string& json);
  // The JSON text of a member's value, "" when there is no such member.
  std::string json(const std::string& key) const;

 private:
  void put(const std::string& key, std::string json);
  std::vector<std::pair<std::string, std::string>> entries_;  // key, JSON text
};

// Peak resident memory of this process in MB (getrusage).
double peakRssMb();

}  // namespace IO
}  // namespace Tribos
