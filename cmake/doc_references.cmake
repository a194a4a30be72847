# The docs.references test (cmake -P): every reference to a document stays inside the repository, and
# every section of docs/DESIGN.md that something cites exists. It fails, one line per reference, on:
#   - DESIGN.md cited other than as docs/DESIGN.md, and STYLE.md cited at all (documents a clone does not
#     have); in a page under docs/, a Markdown link target (DESIGN.md#anchor) is docs/DESIGN.md too;
#   - ../shared/ other than ../shared/testdata (the sample models, which the tests skip without);
#   - docs/DESIGN.md §N or §N.M (also "docs/DESIGN.md §4.1, §4.2") where docs/DESIGN.md has no heading
#     "## N." or "### N.M", or whose section is broken onto the next line, where it would go unchecked.
# Usage: cmake -DROOT=<the source folder> -P cmake/doc_references.cmake
# Every text file under ROOT is read except build trees (build/, or any top-level folder holding a
# CMakeCache.txt), .git, node_modules and this script, whose patterns would match themselves.
cmake_minimum_required(VERSION 3.25)

if(NOT ROOT OR NOT IS_DIRECTORY "${ROOT}")
  message(FATAL_ERROR "docs.references: ROOT '${ROOT}' is not a folder")
endif()

# The sections of docs/DESIGN.md: "## 3. Mathematics" is 3, "### 3.6 Non-rigid joints" is 3.6.
set(design "${ROOT}/docs/DESIGN.md")
if(NOT EXISTS "${design}")
  message(FATAL_ERROR "docs.references: docs/DESIGN.md is missing")
endif()
file(STRINGS "${design}" headings ENCODING UTF-8 REGEX "^##+ [0-9]+(\\.[0-9]+)*\\.? ")
set(sections "")
foreach(heading IN LISTS headings)
  string(REGEX REPLACE "^##+ ([0-9]+(\\.[0-9]+)*)\\.? .*" "\\1" number "${heading}")
  list(APPEND sections "${number}")
endforeach()
list(LENGTH sections section_count)
# A control: a page whose headings this script cannot read would make every citation look broken.
if(section_count LESS 2)
  message(FATAL_ERROR "docs.references: found ${section_count} numbered headings in docs/DESIGN.md; "
                      "expected '## N. Title' and '### N.M Title'")
endif()

# The files to read.
set(binary_extensions png jpg jpeg gif webp exr glb bin ktx2 gz zip tar ico pdf)
file(GLOB top_entries LIST_DIRECTORIES true RELATIVE "${ROOT}" "${ROOT}/*")
set(files "")
foreach(entry IN LISTS top_entries)
  if(entry STREQUAL ".git" OR entry STREQUAL "build" OR entry STREQUAL "node_modules")
    continue()
  endif()
  if(IS_DIRECTORY "${ROOT}/${entry}")
    file(GLOB caches "${ROOT}/${entry}/CMakeCache.txt" "${ROOT}/${entry}/*/CMakeCache.txt")
    if(caches)
      continue()  # a build tree
    endif()
    file(GLOB_RECURSE found LIST_DIRECTORIES false RELATIVE "${ROOT}" "${ROOT}/${entry}/*")
    list(APPEND files ${found})
  else()
    list(APPEND files "${entry}")
  endif()
endforeach()
list(FILTER files EXCLUDE REGEX "(^|/)(node_modules|\\.git)/")
list(REMOVE_ITEM files "cmake/doc_references.cmake")

# A line becomes one list element only when its ';', '[' and ']' (which CMake lists split at, or nest by)
# are out of the way: they stand in as these three control characters while the lines are examined.
string(ASCII 1 semicolon)
string(ASCII 2 open_bracket)
string(ASCII 3 close_bracket)

set(problems "")
set(scanned 0)
set(citations 0)
foreach(file IN LISTS files)
  get_filename_component(extension "${file}" LAST_EXT)
  string(TOLOWER "${extension}" extension)
  string(REGEX REPLACE "^\\." "" extension "${extension}")
  if(extension IN_LIST binary_extensions)
    continue()
  endif()
  math(EXPR scanned "${scanned} + 1")
  file(READ "${ROOT}/${file}" content)
  if(NOT content MATCHES "DESIGN\\.md|STYLE\\.md|\\.\\./shared")
    continue()
  endif()
  # A section broken onto the next line would escape the section check below, which reads line by line.
  if(content MATCHES "docs/DESIGN\\.md[ \t]*\n[ \t]*(//|#|\\*)?[ \t]*§")
    list(APPEND problems
         "${file}: cites docs/DESIGN.md with its section on the next line: keep 'docs/DESIGN.md §N.M' on one line")
  endif()
  string(REPLACE ";" "${semicolon}" content "${content}")
  string(REPLACE "[" "${open_bracket}" content "${content}")
  string(REPLACE "]" "${close_bracket}" content "${content}")
  string(REPLACE "\n" ";" lines "${content}")
  list(FILTER lines INCLUDE REGEX "DESIGN\\.md|STYLE\\.md|\\.\\./shared")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" excerpt)  # its stand-ins are put back when the problems are printed

    # Documents outside the repository.
    string(REPLACE "docs/DESIGN.md" "" rest "${line}")
    if(file MATCHES "^docs/")
      string(REGEX REPLACE "${close_bracket}\\((\\./)?DESIGN\\.md" "" rest "${rest}")
    endif()
    if(rest MATCHES "DESIGN\\.md")
      list(APPEND problems "${file}: cites DESIGN.md other than as docs/DESIGN.md: ${excerpt}")
    endif()
    if(line MATCHES "STYLE\\.md")
      list(APPEND problems "${file}: cites STYLE.md, which is not in the repository: ${excerpt}")
    endif()
    string(REPLACE "../shared/testdata" "" rest "${line}")
    if(rest MATCHES "\\.\\./shared")
      list(APPEND problems "${file}: refers to ../shared/ beyond ../shared/testdata: ${excerpt}")
    endif()

    # Sections of docs/DESIGN.md.
    string(REGEX MATCHALL "docs/DESIGN\\.md §[0-9]+(\\.[0-9]+)*(, §[0-9]+(\\.[0-9]+)*)*" cited "${line}")
    foreach(citation IN LISTS cited)
      string(REGEX MATCHALL "§[0-9]+(\\.[0-9]+)*" numbers "${citation}")
      foreach(number IN LISTS numbers)
        string(REPLACE "§" "" number "${number}")
        math(EXPR citations "${citations} + 1")
        if(NOT number IN_LIST sections)
          list(APPEND problems
               "${file}: cites docs/DESIGN.md §${number}, which docs/DESIGN.md does not have: ${excerpt}")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()

# A control: a tree this script could not read would pass without having checked anything.
if(scanned LESS 50)
  message(FATAL_ERROR "docs.references: read only ${scanned} files under ${ROOT}")
endif()

list(LENGTH problems problem_count)
if(problem_count GREATER 0)
  foreach(problem IN LISTS problems)
    string(REPLACE "${semicolon}" ";" problem "${problem}")
    string(REPLACE "${open_bracket}" "[" problem "${problem}")
    string(REPLACE "${close_bracket}" "]" problem "${problem}")
    message("${problem}")  # one line each, as written
  endforeach()
  message(FATAL_ERROR "docs.references: ${problem_count} references point outside the repository or to a "
                      "missing section of docs/DESIGN.md (listed above)")
endif()
message("docs.references: ${scanned} files read; ${citations} citations of docs/DESIGN.md's ${section_count} "
        "sections, all found; nothing refers outside the repository but ../shared/testdata")
