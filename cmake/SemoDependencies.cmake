# Every third-party library semo uses, found once with the recipe ARCHITECTURE.md gives for its
# Debian bookworm package. Each library target links only what it uses.
find_package(PkgConfig REQUIRED)
pkg_check_modules(Z3 REQUIRED IMPORTED_TARGET z3)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(SUNDIALS REQUIRED)
find_package(urdfdom REQUIRED)
find_package(tinyxml2 REQUIRED)
find_package(fmt REQUIRED)
find_package(CLI11 REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
# libssl-dev: SHA-256 (EVP) for model fingerprints.
find_package(OpenSSL REQUIRED COMPONENTS Crypto)

# urdfdom's config exports plain variables, not a target: wrap them once.
add_library(semo_urdfdom INTERFACE)
target_include_directories(semo_urdfdom SYSTEM INTERFACE ${urdfdom_INCLUDE_DIRS})
target_link_libraries(semo_urdfdom INTERFACE ${urdfdom_LIBRARIES})

# libbdd-dev (BuDDy 2.4): the decision diagrams of the symbolic liveness search. It ships neither a
# CMake package nor a pkg-config file: the header and the library are found directly.
find_path(BUDDY_INCLUDE_DIR bdd.h REQUIRED)
find_library(BUDDY_LIBRARY bdd REQUIRED)
add_library(semo_buddy INTERFACE)
target_include_directories(semo_buddy SYSTEM INTERFACE ${BUDDY_INCLUDE_DIR})
target_link_libraries(semo_buddy INTERFACE ${BUDDY_LIBRARY})
