#!/usr/bin/env bash
# sdk_surface_test.sh LIBRARY INCLUDE_DIR: what a program linking the
# client SDK sees. The public headers include only standard headers and
# each other (no gRPC, protobuf, Abseil or Eigen); the library exports no
# symbol of those, none that takes or gives one, and none of the
# project's internal code (hs::, the generated haptics::v1 messages, the
# classes' hidden Impl): only haptics::, the hs_ C functions, and the
# standard library's templates instantiated inside it.
set -euo pipefail
library=$1
include=$2
status=0

foreign=$(grep -h '^#include' "$include"/haptics/*.h \
  | grep -v -E '^#include (<[a-z_]+(\.h)?>|"haptics/[a-z_]+\.h")$' || true)
if [ -n "$foreign" ]; then
  echo "FAIL: public headers include more than the standard library and haptics/:" >&2
  echo "$foreign" >&2
  status=1
fi

# "ADDRESS TYPE NAME" lines; the name is the rest of the line. Template
# arguments are dropped before looking (std::thread's state names the
# internal class it runs, and that is the standard library's symbol), so
# that what remains is each symbol's own name, return type and parameters.
exported=$(nm -DC --defined-only "$library" | cut -d' ' -f3-)
leaked=$(echo "$exported" | sed -E ':a; s/<[^<>]*>//g; ta' \
  | grep -E '(^|[ (,])(grpc|grpc_impl|google|absl|Eigen|hs|haptics::v1|haptics::internal)::|::Impl::' \
  || true)
if [ -n "$leaked" ]; then
  echo "FAIL: the library exports internal symbols:" >&2
  echo "$leaked" | head -20 >&2
  status=1
fi
echo "$exported" | grep -q '^haptics::Session::Connect' || { echo "FAIL: no haptics::Session::Connect" >&2; status=1; }
echo "$exported" | grep -q '^hs_session_open$' || { echo "FAIL: no hs_session_open" >&2; status=1; }
[ $status -eq 0 ] && echo "ok: $(echo "$exported" | wc -l) symbols exported"
exit $status
