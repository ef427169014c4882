// Tribos_ByteBuffer.hpp: plain data (numbers, vectors of numbers, strings)
// packed into bytes, to be sent to one rank or broadcast to all in one
// message (in pieces of at most 1 GiB: MPI counts are int).
#pragma once

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "Tribos_Error.hpp"
#include "Tribos_Types.hpp"

namespace Tribos {

class ByteBuffer {
 public:
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable<T>::value, "ByteBuffer holds plain data");
    append(&value, sizeof(T));
  }
  template <class T>
  void put(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable<T>::value, "ByteBuffer holds plain data");
    put(static_cast<long long>(values.size()));
    append(values.data(), values.size() * sizeof(T));
  }
  void put(const std::string& s) {
    put(static_cast<long long>(s.size()));
    append(s.data(), s.size());
  }

  template <class T>
  T get() {
    T value;
    take(&value, sizeof(T));
    return value;
  }
  template <class T>
  std::vector<T> getVector() {
    std::vector<T> values(static_cast<size_t>(get<long long>()));
    take(values.data(), values.size() * sizeof(T));
    return values;
  }
  std::string getString() {
    std::string s(static_cast<size_t>(get<long long>()), '\0');
    take(&s[0], s.size());
    return s;
  }
  // The twin of put for code that lists its fields once for both ways:
  // value becomes what put(value) packed.
  template <class T>
  void read(T& value) {
    value = get<T>();
  }
  template <class T>
  void read(std::vector<T>& values) {
    values = getVector<T>();
  }
  void read(std::string& s) { s = getString(); }

  std::vector<char>& bytes() { return bytes_; }
  bool consumed() const { return at_ == bytes_.size(); }

 private:
  void append(const void* p, size_t n) {
    const size_t at = bytes_.size();
    bytes_.resize(at + n);
    if (n > 0) std::memcpy(&bytes_[at], p, n);
  }
  void take(void* p, size_t n) {
    TRIBOS_REQUIRE(at_ + n <= bytes_.size(), "ByteBuffer: read past the end of the packed data");
    if (n > 0) std::memcpy(p, &bytes_[at_], n);
    at_ += n;
  }
  std::vector<char> bytes_;
  size_t at_ = 0;
};

namespace detail {
// Calls piece(at, n) for consecutive pieces of at most 1 GiB covering size bytes.
template <class F>
void forEachPiece(size_t size, F piece) {
  constexpr size_t kPiece = size_t(1) << 30;
  for (size_t at = 0; at < size; at += kPiece) piece(at, static_cast<int>(std::min(kPiece, size - at)));
}
}  // namespace detail

// Point to point: the size, then the bytes in pieces.
inline void sendBuffer(ByteBuffer& buffer, int destination, const Comm& comm) {
  long long size = static_cast<long long>(buffer.bytes().size());
  Teuchos::send(comm, 1, &size, destination);
  detail::forEachPiece(buffer.bytes().size(),
                       [&](size_t at, int n) { Teuchos::send(comm, n, &buffer.bytes()[at], destination); });
}

inline ByteBuffer receiveBuffer(int source, const Comm& comm) {
  long long size = 0;
  Teuchos::receive(comm, source, 1, &size);
  ByteBuffer buffer;
  buffer.bytes().resize(static_cast<size_t>(size));
  detail::forEachPiece(buffer.bytes().size(),
                       [&](size_t at, int n) { Teuchos::receive(comm, source, n, &buffer.bytes()[at]); });
  return buffer;
}

// Collective: every rank ends with root's bytes.
inline void broadcastBuffer(ByteBuffer& buffer, int root, const Comm& comm) {
  long long size = static_cast<long long>(buffer.bytes().size());
  Teuchos::broadcast(comm, root, &size);
  if (comm.getRank() != root) buffer = ByteBuffer(), buffer.bytes().resize(static_cast<size_t>(size));
  detail::forEachPiece(buffer.bytes().size(),
                       [&](size_t at, int n) { Teuchos::broadcast(comm, root, n, &buffer.bytes()[at]); });
}

}  // namespace Tribos
