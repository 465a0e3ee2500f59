// An outside project against the installed trigrav::colmap (SQLite through find_dependency): an
// empty file is an SQLite database without COLMAP's tables, and a gravity CSV round trip.
#include <trigrav/colmap/database.h>
#include <trigrav/colmap/gravity_csv.h>

#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::string folder = argv[1];
  std::ofstream(folder + "/empty.db").close();
  std::string message;
  try {
    trigrav::colmap::Database database(folder + "/empty.db");
  } catch (const std::runtime_error& error) {
    message = error.what();
  }
  const trigrav::colmap::GravityByImageName gravity = {{"a.png", Eigen::Vector3d(0, 1, 0.5)}};
  trigrav::colmap::WriteGravityCsv(gravity, folder + "/gravity.csv");
  const bool same = trigrav::colmap::ReadGravityCsv(folder + "/gravity.csv") == gravity;
  std::cout << "trigrav::colmap: " << message << "; gravity CSV round trip "
            << (same ? "equal" : "DIFFERENT") << "\n";
  return same && message.find("not a COLMAP database") != std::string::npos ? 0 : 1;
}
