# The benchmark programs' command lines (CTest asm_benchmark_command_lines,
# label "benchmark"): each bad argument exits with status 2 and a message
# naming the option and the value, before any work; an input that cannot be
# read exits with status 1, naming it; a PLY with NaN coordinates runs.
#
#   cmake -DQUALITY=... -DSPEED=... -DPROFILE=... -DPARTITION=... -DWORK=dir
#         -P CommandLineTest.cmake
cmake_minimum_required(VERSION 3.16)

set(_failures 0)

# check(STATUS REGEX PROGRAM ARGS...): runs PROGRAM ARGS..., expects the
# exit status STATUS and REGEX in its stdout + stderr (with status 2: one
# line on stderr and nothing on stdout).
function(check status regex program)
  execute_process(COMMAND ${program} ${ARGN}
    WORKING_DIRECTORY "${WORK}"
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
  get_filename_component(name "${program}" NAME)
  string(REPLACE ";" " " shown "${ARGN}")
  # A usage error: one line on stderr, nothing on stdout.
  set(one_line TRUE)
  if (status EQUAL 2)
    string(REGEX MATCHALL "\n" newlines "${err}")
    list(LENGTH newlines lines)
    if (NOT lines EQUAL 1 OR NOT out STREQUAL "")
      set(one_line FALSE)
    endif ()
  endif ()
  if (NOT rc STREQUAL "${status}" OR NOT "${out}${err}" MATCHES "${regex}" OR NOT one_line)
    message("FAIL: ${name} ${shown}: exit ${rc} (expected ${status}), expected /${regex}/ in:\n${err}${out}")
    math(EXPR n "${_failures} + 1")
    set(_failures ${n} PARENT_SCOPE)
  else ()
    message("ok:   ${name} ${shown} -> ${rc}")
  endif ()
endfunction()

file(MAKE_DIRECTORY "${WORK}/sub")
# A small PLY (a bumpy 40 x 40 height field) with three NaN points, twice
# under one name; an empty file; a file that is not a PLY.
set(_vertices "")
set(_count 0)
foreach (i RANGE 39)
  foreach (j RANGE 39)
    math(EXPR z "(${i} * ${i} + 3 * ${j} * ${j} + ${i} * ${j}) % 17")
    string(APPEND _vertices "${i} ${j} ${z}\n")
    math(EXPR _count "${_count} + 1")
  endforeach ()
endforeach ()
string(APPEND _vertices "nan 1 2\n3 nan 4\nnan nan nan\n")
math(EXPR _count "${_count} + 3")
set(_ply "ply\nformat ascii 1.0\nelement vertex ${_count}\nproperty float x\nproperty float y\nproperty float z\nend_header\n${_vertices}")
file(WRITE "${WORK}/nan.ply" "${_ply}")
file(WRITE "${WORK}/sub/nan.ply" "${_ply}")
file(WRITE "${WORK}/empty.ply" "")
file(WRITE "${WORK}/text.ply" "not a PLY file\n")

# asm_profile
check(2 "--runs: \"0\"" "${PROFILE}" --runs 0)
check(2 "--runs: missing value" "${PROFILE}" --runs)
check(2 "--runs: \"abc\"" "${PROFILE}" --runs abc)
check(2 "--dump: cannot write \"/nonexistent/x.txt\"" "${PROFILE}" --dump /nonexistent/x.txt)
check(2 "--mode: \"bogus\"" "${PROFILE}" --mode bogus)
check(2 "--points: \"abc\"" "${PROFILE}" --points abc)
check(2 "--points: \"0\"" "${PROFILE}" --points 0)
check(2 "--points: \"-5\"" "${PROFILE}" --points -5)
check(2 "--points: \"1e12\" is more than" "${PROFILE}" --points 1e12)
check(2 "--fraction: \"0\"" "${PROFILE}" --fraction 0)
check(2 "--fraction: \"nan\"" "${PROFILE}" --fraction nan)
check(2 "--fraction: \"inf\"" "${PROFILE}" --fraction inf)
check(2 "--fraction: \"2\"" "${PROFILE}" --fraction 2)
check(2 "--threads: \"0\"" "${PROFILE}" --threads 0)
check(2 "--threads: \"-3\"" "${PROFILE}" --threads -3)
check(2 "--ply: missing value" "${PROFILE}" --ply)
check(1 "no points read from .*empty.ply" "${PROFILE}" --ply empty.ply --runs 1)
check(1 "no points read from .*text.ply" "${PROFILE}" --ply text.ply --runs 1)
check(1 "no points read from .*missing.ply" "${PROFILE}" --ply missing.ply --runs 1)
check(0 "points" "${PROFILE}" --ply nan.ply --runs 1 --dump dump.txt)

# asm_partition
check(0 "usage: asm_partition" "${PARTITION}" --help)
check(2 "--processes: \"0\"" "${PARTITION}" --processes 0)
check(2 "--processes: \"abc\"" "${PARTITION}" --processes abc)
check(2 "--processes: \",\"" "${PARTITION}" --processes ,)
check(2 "--processes: \"-2\"" "${PARTITION}" --processes -2)
check(2 "--fraction: \"0\"" "${PARTITION}" --fraction 0)
check(2 "--fraction: \"-1\"" "${PARTITION}" --fraction -1)
check(2 "--fraction: \"nan\"" "${PARTITION}" --fraction nan)
check(2 "--fraction: \"5\"" "${PARTITION}" --fraction 5)
check(2 "--halo: \"-1\"" "${PARTITION}" --halo -1)
check(2 "--halo: missing value" "${PARTITION}" --halo)
check(2 "--input: \"bumps:1e12\"" "${PARTITION}" --input bumps:1e12)
check(1 "no points in missing.ply" "${PARTITION}" --input missing.ply)
check(0 "\\| 2 \\| 6 \\|" "${PARTITION}" --input nan.ply --processes 2 --halo 6)

# Both benchmarks
foreach (program IN ITEMS "${QUALITY}" "${SPEED}")
  foreach (value IN ITEMS 0 abc nan inf -0.5 , 1.5 0.05,0.05)
    check(2 "--fractions: \"" "${program}" --fractions ${value})
  endforeach ()
  check(2 "--fractions: missing value" "${program}" --fractions)
  check(2 "--inputs: \",\"" "${program}" --inputs ,)
  check(2 "input: \"bumps:abc\"" "${program}" --inputs bumps:abc)
  check(2 "input: \"cube:10k\"" "${program}" --inputs cube:10k)
  check(2 "input: \"bumps:1e12\": \"1e12\" is more than" "${program}" --inputs bumps:1e12)
  check(2 "--inputs .*--quick" "${program}" --quick --inputs bumps:1k)
  foreach (peer IN ITEMS "vtkVoxelGrid" "vtkMaskPoints random" "CGAL grid" "ASM default")
    check(2 "--asm: \"${peer}\"" "${program}" --asm "${peer}:FillHoles=0")
  endforeach ()
  check(1 "missing.ply" "${program}" --fractions 0.05 --inputs missing.ply,empty.ply,text.ply)
endforeach ()
check(0 "N = 1600.*ASM default +[0-9]+ +[0-9.e+-]+ +[0-9].*3 point\\(s\\) of nan.ply with a NaN" "${QUALITY}" --fractions 0.05 --inputs nan.ply)

# asm_speed_benchmark
foreach (value IN ITEMS , 0 abc 1,1 -1)
  check(2 "--threads: \"" "${SPEED}" --threads ${value})
endforeach ()
foreach (value IN ITEMS 0 -5 abc)
  check(2 "--runs: \"${value}\"" "${SPEED}" --runs ${value})
endforeach ()
check(2 "--threads cannot be given with --readme" "${SPEED}" --readme --threads 1)
check(2 "--quick cannot be given with --readme" "${SPEED}" --readme --quick)
check(2 "--runs cannot be given with --quick" "${SPEED}" --quick --runs 2)
# With --cgal when this build has CGAL (--cgal is refused otherwise).
execute_process(COMMAND "${SPEED}" --cgal --help RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
set(_cgal)
if (rc EQUAL 0)
  set(_cgal --cgal)
endif ()
check(0 "nan#2" "${SPEED}" ${_cgal} --inputs nan.ply,sub/nan.ply --fractions 0.05 --runs 1
  --threads 1 --no-memory)

if (_failures GREATER 0)
  message(FATAL_ERROR "${_failures} command line(s) failed")
endif ()
