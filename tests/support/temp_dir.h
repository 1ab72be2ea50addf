#pragma once
// A fresh, empty temporary folder for a test, removed with everything in it when the TempDir goes.
// Named after the test (or the name given, for a suite's shared folder) and this process, so that
// tests running in parallel never share one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace spume::testing {

class TempDir {
 public:
  // The current test's folder: spume_test_<suite>_<test>_<pid> (parameterised names made file-safe).
  TempDir() : TempDir(current_test_name()) {}
  // A folder named `name` (and the pid), e.g. for a suite's SetUpTestSuite, where no test runs yet.
  explicit TempDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() / ("spume_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path path;

  std::filesystem::path operator/(const std::filesystem::path& relative) const { return path / relative; }

  // Writes `bytes` to the file `name` in the folder (its parent folders made); returns its path.
  std::filesystem::path write(const std::filesystem::path& name, const std::string& bytes) const {
    const std::filesystem::path p = path / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
  // A one-byte file `name`: a file that exists, whatever it holds.
  void touch(const std::filesystem::path& name) const { write(name, "x"); }

 private:
  static std::string current_test_name() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "no_test";
    for (char& c : name)
      if (c == '/') c = '_';
    return name;
  }
};

}  // namespace spume::testing
