# Precompiled headers: the heavy headers most translation units include
# (the standard library, Eigen, gRPC and the service's messages, CLI11,
# nlohmann-json; GoogleTest for the tests) are parsed once per build
# instead of once per file: with line tables only (HS_DEBUG_INFO), a cold
# build on two cores went from 42.5 to about 27 min (2026-11-28).
#
# Each set is built by a host target of its own (cmake/precompiled_headers.cc,
# an empty translation unit) and reused by the targets that include those
# headers (REUSE_FROM). Reuse needs the same compiler flags, and clang also
# refuses a header built with a macro the reusing file lacks, so each host
# defines only what every one of its users defines.

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
