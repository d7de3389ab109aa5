// Plain values to bytes and back, for what the ranks of a distributed render send each other
// (film pixels, profiles): the sender and receiver are the same program, so values travel in
// their in-memory form. A reader that runs past the end throws std::runtime_error.
#pragma once

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace tessera {

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const char* p = reinterpret_cast<const char*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof value);
  }
  template <typename T>
  void put_vector(const std::vector<T>& values) {
    put(values.size());
    for (const T& v : values) put(v);
  }
  std::vector<char> take() { return std::move(bytes_); }

 private:
  std::vector<char> bytes_;
};

class ByteReader {
 public:
  // `what` names the data in the error, e.g. "a rank's tile data".
  ByteReader(const std::vector<char>& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}
  template <typename T>
  void get(T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    if (at_ + sizeof value > bytes_.size()) throw std::runtime_error(what_ + " is shorter than it says");
    std::memcpy(&value, bytes_.data() + at_, sizeof value);
    at_ += sizeof value;
  }
  template <typename T>
  T get() {
    T value{};
    get(value);
    return value;
  }
  template <typename T>
  std::vector<T> get_vector() {
    const auto n = get<std::size_t>();
    if (n > (bytes_.size() - at_) / std::max<std::size_t>(1, sizeof(T))) throw std::runtime_error(what_ + " is shorter than it says");
    std::vector<T> values(n);
    for (T& v : values) get(v);
    return values;
  }

 private:
  const std::vector<char>& bytes_;
  std::string what_;
  std::size_t at_ = 0;
};

}  // namespace tessera
