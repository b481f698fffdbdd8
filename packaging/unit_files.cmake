# haptic-server's systemd unit and its defaults file, written for one
# install prefix. packaging/CMakeLists.txt calls this at install time, for
# the prefix given then (`cmake --install --prefix P`, or /usr under
# cpack), and at configure time for /usr (the packages' files, which
# tests/deploy/manifests_test.py checks).
#
#   hs_write_unit_files(SOURCE_DIR PREFIX BINDIR DATADIR OUT_DIR)
#
# writes OUT_DIR/haptic-server.service and OUT_DIR/haptic-server.default,
# and sets HS_UNIT_DIR and HS_DEFAULT_DIR to where they go: under /usr
# where the distribution keeps them (/lib/systemd/system, /etc/default),
# elsewhere beside the prefix's own files (PREFIX/lib/systemd/system,
# PREFIX/etc/default). BINDIR and DATADIR are relative to PREFIX.
function(hs_write_unit_files source_dir prefix bindir datadir out_dir)
  if(prefix STREQUAL "/usr")
    set(HS_SYSCONFDIR /etc)
    set(unit_dir /lib/systemd/system)
  else()
    set(HS_SYSCONFDIR ${prefix}/etc)
    set(unit_dir ${prefix}/lib/systemd/system)
  endif()
  set(HS_BINDIR ${prefix}/${bindir})
  set(HS_DATADIR ${prefix}/${datadir})
  configure_file(${source_dir}/haptic-server.service.in ${out_dir}/haptic-server.service @ONLY)
  configure_file(${source_dir}/haptic-server.default.in ${out_dir}/haptic-server.default @ONLY)
  set(HS_UNIT_DIR ${unit_dir} PARENT_SCOPE)
  set(HS_DEFAULT_DIR ${HS_SYSCONFDIR}/default PARENT_SCOPE)
endfunction()
