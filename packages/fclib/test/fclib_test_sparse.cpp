// FCLIB matrices (LocalCsr) read from each storage and their products, the
// compressed-column path of the reader (no sample uses it), and the error
// message for a missing dataset.
#include <Teuchos_UnitTestHarness.hpp>
#include <hdf5.h>

#include <cstdio>

#include "Tribos_FCLIB.hpp"
#include "fclib_test_util.hpp"

using namespace Tribos;
using namespace Tribos::FCLIB;

namespace {

// A = [ 1 0 2 ]
//     [ 0 0 3 ]
//     [ 4 5 0 ]
//     [ 0 6 0 ]
const int kRows = 4, kCols = 3;
const double kDense[kRows][kCols] = {{1, 0, 2}, {0, 0, 3}, {4, 5, 0}, {0, 6, 0}};

LocalCsr fromCSCExample() {
  return fromCSC(kRows, kCols, {0, 2, 4, 6}, {0, 2, 3, 2, 1, 0},
                               {1, 4, 6, 5, 3, 2}, "csc");
}

void checkConversions(Teuchos::FancyOStream& out, bool& success) {
  const LocalCsr csr =
      fromCSR(kRows, kCols, {0, 2, 3, 5, 6}, {2, 0, 2, 1, 0, 1},
                            {2, 1, 3, 5, 4, 6}, "csr");  // unsorted rows on purpose
  const LocalCsr csc = fromCSCExample();
  // Triplets in scrambled order, with (2,0) split into 1 + 3.
  const LocalCsr tri = fromTriplets(
      kRows, kCols, {3, 2, 0, 1, 2, 0, 2}, {1, 0, 2, 2, 1, 0, 0}, {6, 1, 2, 3, 5, 1, 3}, "tri");
  TEST_ASSERT(bitwiseEqual(csr, csc));  // CSR and CSC differ
  TEST_ASSERT(bitwiseEqual(csr, tri));  // CSR and triplets differ
  TEST_EQUALITY(csr.nnz(), 6);

  const std::vector<double> x = {1, -2, 3}, y = {1, 2, -1, 0.5};
  std::vector<double> Ax, Aty;
  csr.multiply(x, Ax);
  csr.multiplyTranspose(y, Aty);
  for (int i = 0; i < kRows; ++i) {
    double s = 0;
    for (int j = 0; j < kCols; ++j) s += kDense[i][j] * x[j];
    TEST_EQUALITY(Ax[i], s);  // A x row
  }
  for (int j = 0; j < kCols; ++j) {
    double s = 0;
    for (int i = 0; i < kRows; ++i) s += kDense[i][j] * y[i];
    TEST_EQUALITY(Aty[j], s);  // A' y column
  }
}

template <typename F>
void expectThrow(F f, const std::string& what, Teuchos::FancyOStream& out, bool& success) {
  try {
    f();
    TEST_ASSERT(false);  // no exception
  } catch (const std::runtime_error& e) {
    std::cout << "expected error: " << e.what() << std::endl;
  }
}

void checkValidation(Teuchos::FancyOStream& out, bool& success) {
  expectThrow([] { fromTriplets(2, 2, {0, 2}, {0, 0}, {1, 1}, "row out of range"); },
              "row out of range", out, success);
  expectThrow([] { fromCSR(2, 2, {0, 2, 1}, {0, 1}, {1, 1}, "bad pointers"); },
              "decreasing pointers", out, success);
  expectThrow([] { fromCSC(2, 2, {0, 1, 3}, {0, 1}, {1, 1}, "short"); },
              "pointers past the data", out, success);
}

void writeInt(hid_t g, const char* name, int v) {
  hsize_t one = 1;
  hid_t s = H5Screate_simple(1, &one, nullptr);
  hid_t d = H5Dcreate2(g, name, H5T_STD_I32LE, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, &v);
  H5Dclose(d);
  H5Sclose(s);
}

template <typename T>
void writeArray(hid_t g, const char* name, hid_t fileType, hid_t memType, const std::vector<T>& v) {
  hsize_t n = v.size();
  hid_t s = H5Screate_simple(1, &n, nullptr);
  hid_t d = H5Dcreate2(g, name, fileType, s, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dwrite(d, memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(d);
  H5Sclose(s);
}

// A hand-made global file whose H (4 x 3, one contact) is stored as compressed
// columns; M = identity as triplets. 'withW' false leaves out vectors/w.
void writeHandMadeGlobal(const std::string& path, bool withW) {
  hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  hid_t g = H5Gcreate2(file, "fclib_global", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  hid_t H = H5Gcreate2(g, "H", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  writeInt(H, "nzmax", 6);
  writeInt(H, "m", kRows);
  writeInt(H, "n", kCols);
  writeInt(H, "nz", -1);
  writeArray<int>(H, "p", H5T_STD_I32LE, H5T_NATIVE_INT, {0, 2, 4, 6});
  writeArray<int>(H, "i", H5T_STD_I32LE, H5T_NATIVE_INT, {0, 2, 3, 2, 1, 0});
  writeArray<double>(H, "x", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {1, 4, 6, 5, 3, 2});
  H5Gclose(H);
  hid_t M = H5Gcreate2(g, "M", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  writeInt(M, "nzmax", 4);
  writeInt(M, "m", kRows);
  writeInt(M, "n", kRows);
  writeInt(M, "nz", 4);
  writeArray<int>(M, "p", H5T_STD_I32LE, H5T_NATIVE_INT, {0, 1, 2, 3});
  writeArray<int>(M, "i", H5T_STD_I32LE, H5T_NATIVE_INT, {0, 1, 2, 3});
  writeArray<double>(M, "x", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {1, 1, 1, 1});
  H5Gclose(M);
  hid_t v = H5Gcreate2(g, "vectors", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  writeArray<double>(v, "f", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {0, 0, 0, 0});
  writeArray<double>(v, "mu", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {0.3});
  if (withW) writeArray<double>(v, "w", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {0, 0, 0});
  H5Gclose(v);
  writeInt(g, "spacedim", 3);
  H5Gclose(g);
  H5Fclose(file);
}

void checkCompressedColumnFile(Teuchos::FancyOStream& out, bool& success) {
  const std::string path = fclib_test::scratchPath("sparse", "csc.hdf5");
  writeHandMadeGlobal(path, true);
  const GlobalProblem P = readGlobal(path);
  TEST_ASSERT(bitwiseEqual(P.H, fromCSCExample()));  // H read from a CSC file
  TEST_ASSERT(readInfo(path).title.empty());  // missing info is empty

  writeHandMadeGlobal(path, false);
  try {
    readGlobal(path);
    TEST_ASSERT(false);  // missing w not detected
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    std::cout << "expected error: " << what << std::endl;
    TEST_EQUALITY(what, "FCLIB file " + path + ": group /fclib_global/vectors has no dataset w");
  }
  std::remove(path.c_str());
}

}  // namespace

TEUCHOS_UNIT_TEST(SparseMatrix, Conversions) { checkConversions(out, success); }
TEUCHOS_UNIT_TEST(SparseMatrix, Validation) { checkValidation(out, success); }
TEUCHOS_UNIT_TEST(SparseMatrix, CompressedColumnFile) { checkCompressedColumnFile(out, success); }

// The entry farthest from its mirror, a mirror that is not stored counting as 0.
TEUCHOS_UNIT_TEST(SparseMatrix, LargestAsymmetry) {
  // [ 2   1   0 ]
  // [ 1.5 3   4 ]   (2, 1) not stored: |4 - 0| is the largest difference
  // [ 0   0   5 ]
  const LocalCsr A = fromCSR(3, 3, {0, 2, 5, 6}, {0, 1, 0, 1, 2, 2}, {2, 1, 1.5, 3, 4, 5}, "A");
  const Asymmetry worst = largestAsymmetry(A);
  TEST_EQUALITY(worst.row, 1);
  TEST_EQUALITY(worst.col, 2);
  TEST_EQUALITY(worst.value, 4.0);
  TEST_EQUALITY(worst.mirror, 0.0);
  TEST_EQUALITY(asymmetry(A), 4.0);
  const LocalCsr S = fromCSR(2, 2, {0, 2, 4}, {0, 1, 0, 1}, {2, -1, -1, 2}, "S");
  TEST_EQUALITY(largestAsymmetry(S).row, -1);
  TEST_EQUALITY(asymmetry(S), 0.0);
}
