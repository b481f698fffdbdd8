# A precompiled header for the service's libraries and programs: the heavy
# headers they include (the standard library, Eigen, gRPC and the
# service's messages, CLI11, nlohmann-json) are parsed once per build
# instead of once per file. It saves a quarter of the time of a file that
# uses CLI11 or nlohmann-json (drive_command.cc: 14.3 against 19 s) and
# costs a little where it is loaded for less (haptic_server.cc: 17 against
# 15 s; 2026-11-29, GCC 12, one file at a time on the 2-core VM).
#
# The tests have none. GCC's header for them (GoogleTest with the above)
# came out different at each build of the same sources, and ccache hashes
# it into every file that uses it, so no test compiled in one clone was
# found in ccache by another's build; parsed per file, a test takes about
# as long (stream_registry_test.cc 8.4 s either way, triangle_sat_test.cc
# 20.5 against 19.2 s, drive_command_test.cc 25.5 against 18.7 s). GCC's
# header of the service is the same at every build. scripts/sanitize.sh
# builds with none: clang's hold the build folder's path.
#
# The header is built by a host target of its own
# (cmake/precompiled_headers.cc, an empty translation unit) and reused by
# the targets that include those headers (REUSE_FROM). Reuse needs the
# same compiler flags, and clang also refuses a header built with a macro
# the reusing file lacks, so the host defines only what every one of its
# users defines.

# The service's libraries and programs (client and server): every one of
# them defines BOOST_ALL_NO_LIB (Boost::headers through hs_hash or hs_server).
add_library(hs_service_pch STATIC ${CMAKE_CURRENT_LIST_DIR}/precompiled_headers.cc)
target_link_libraries(hs_service_pch PRIVATE hs_proto Eigen3::Eigen CLI11::CLI11 nlohmann_json::nlohmann_json)
target_compile_definitions(hs_service_pch PRIVATE BOOST_ALL_NO_LIB)
target_precompile_headers(hs_service_pch PRIVATE
  <algorithm> <atomic> <chrono> <filesystem> <fstream> <functional> <iostream> <map> <memory>
  <mutex> <optional> <sstream> <string> <thread> <vector>
  <Eigen/Geometry> <CLI/CLI.hpp> <nlohmann/json.hpp> <grpcpp/grpcpp.h>
  <haptics/v1/session_service.grpc.pb.h> <haptics/v1/scene_service.grpc.pb.h>)

# hs_use_service_pch(target...): the targets parse the service's headers
# from hs_service_pch's precompiled header.
function(hs_use_service_pch)
  foreach(target ${ARGN})
    target_precompile_headers(${target} REUSE_FROM hs_service_pch)
  endforeach()
endfunction()
