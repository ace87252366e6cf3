#!/usr/bin/env bash
# check_layering.sh SOURCE_DIR KERNELS_ARCHIVE [NM]
# Enforces the layer table of ARCHITECTURE.md:
#   kernels/  : libm/freestanding headers and its own headers only; the static archive
#               needs only libm symbols and memset/memcpy (nm -u) and holds no mutable
#               global or static data;
#   c_api/    : kernels + libc: no Trilinos, MPI, METIS, cJSON, LAPACK or C++ headers,
#               no headers of shim_cxx/ or problems/;
#   shim_cxx/ : c_api + Trilinos/MPI/METIS/LAPACK: no kernel, cJSON or problems/ headers;
#   problems/ : the public c_api headers (rodnet.h, rodnet_solve.h, rodnet_model.h,
#               rodnet_contact.h, rodnet_couple.h, rodnet_ring.h, rodnet_registry.h) + cJSON
#               + libc only;
# and, inside each layer, the order of its folders (check_folder_order.sh with
# folder_order.txt beside this script).
# Prints every violation and exits 1 if there is any.
set -uo pipefail
src=$1
archive=$2
nm=${3:-nm}
bad=0
violation() { echo "layering: $*"; bad=1; }

# Forbidden outside shim_cxx/: Trilinos, Kokkos, MPI, METIS, LAPACK/BLAS.
heavy='(^|/)(mpi|mpi_.*|metis|parmetis|lapacke?|cblas|f77blas)\.h$|^(Teuchos|Tpetra|ROL|Belos|NOX|Thyra|Stratimikos|Kokkos|Epetra|Ifpack2?|Amesos2?|MueLu|Xpetra|Zoltan2?|KokkosKernels|Tsqr|Anasazi)[_A-Za-z0-9]*\.h(pp)?$'
cjson='(^|/)cJSON(_Utils)?\.h$'
freestanding='^(math|stddef|stdint|string|float|limits|stdbool)\.h$'

# Print "file:line:kind:name" for every #include of the given files (one awk
# for all: a process per file or per include is slow on a loaded machine).
includes() {
  printf '%s\0' "$@" | xargs -0 -r awk '
      /^[ \t]*#[ \t]*include[ \t]*[<"]/ {
        line = $0; sub(/^[ \t]*#[ \t]*include[ \t]*/, "", line)
        kind = substr(line, 1, 1); close_ch = (kind == "<") ? ">" : "\""
        name = substr(line, 2); sub(close_ch ".*", "", name)
        print FILENAME ":" FNR ":" kind ":" name
      }'
}
sources() { find "$src/$1" -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \) 2>/dev/null | sort; }
# A quoted include "x" of a file resolves to an existing file under one of the
# folders: beside the including file, or from the folder's root or its include/
# (the public headers).  A ".." may not lead out of the allowed folders.
resolves_in() {
  local name=$1 from=$2; shift 2
  local dir root
  case $name in *..*) return 1 ;; esac
  for dir in "$@"; do
    case ${from%/*}/ in
      "$src/$dir"/*) [ -f "${from%/*}/$name" ] && return 0 ;;
    esac
    for root in "$src/$dir" "$src/$dir/include"; do
      [ -f "$root/$name" ] && return 0
    done
  done
  return 1
}
public_api='^(rodnet|rodnet_solve|rodnet_model|rodnet_contact|rodnet_couple|rodnet_ring|rodnet_registry)\.h$'
# The names of the headers below problems/ (kernels, c_api, shim_cxx), once.
declare -A lower_header
while IFS= read -r h; do lower_header[$h]=1; done < <(
  find "$src/kernels" "$src/c_api" "$src/shim_cxx" -type f -printf '%f\n' 2>/dev/null)

check_layer() {
  local layer=$1; shift
  local files; mapfile -t files < <(sources "$layer")
  [ ${#files[@]} -gt 0 ] || { echo "layering: note: no sources in $layer/ yet"; return; }
  local rec file line kind name base rel
  while IFS= read -r rec; do
    file=${rec%%:*}; rec=${rec#*:}; line=${rec%%:*}; rec=${rec#*:}
    kind=${rec%%:*}; name=${rec#*:}; base=${name##*/}
    rel=${file#"$src"/}
    case $layer in
      kernels)
        if [ "$kind" = '<' ]; then
          [[ $name =~ $freestanding ]] || violation "$rel:$line: kernels may include only libm/freestanding headers, not <$name>"
        else
          resolves_in "$name" "$file" kernels || violation "$rel:$line: kernels may include only their own headers, not \"$name\""
        fi ;;
      c_api)
        if [[ $base =~ $heavy || $base =~ $cjson || $name =~ $cjson ]]; then
          violation "$rel:$line: c_api must not include <$name> (Trilinos/MPI/METIS/LAPACK/cJSON)"
        elif [ "$kind" = '<' ]; then
          [[ $name == *.h ]] || violation "$rel:$line: c_api is C: <$name> is not a C header"
        else
          resolves_in "$name" "$file" c_api kernels || violation "$rel:$line: c_api may include only c_api/ and kernels/ headers, not \"$name\""
        fi ;;
      shim_cxx)
        if [[ $name =~ $cjson ]] || [ "$base" = rnk.h ]; then
          violation "$rel:$line: shim_cxx must not include $name (it uses c_api only)"
        elif [ "$kind" = '"' ]; then
          resolves_in "$name" "$file" shim_cxx c_api || violation "$rel:$line: shim_cxx may include only shim_cxx/ and c_api/ headers, not \"$name\""
        fi ;;
      problems)
        if [[ $base =~ $heavy ]]; then
          violation "$rel:$line: problems must not include $name (Trilinos/MPI/METIS/LAPACK)"
        elif [ "$kind" = '<' ]; then
          if [[ $base =~ $public_api || $name =~ $cjson ]]; then :
          elif [[ $name != *.h ]]; then violation "$rel:$line: problems is C: <$name> is not a C header"
          elif [ -n "${lower_header[$base]:-}" ]; then
            violation "$rel:$line: problems may use only the public headers rodnet.h/rodnet_solve.h, not <$name>"
          fi
        else
          if [[ $base =~ $public_api ]]; then
            resolves_in "$name" "$file" c_api || violation "$rel:$line: \"$name\" does not resolve to c_api/"
          else
            resolves_in "$name" "$file" problems || violation "$rel:$line: problems may include only its own headers and rodnet.h/rodnet_solve.h, not \"$name\""
          fi
        fi ;;
    esac
  done < <(includes "${files[@]}")
}

for layer in kernels c_api shim_cxx problems; do check_layer "$layer"; done

# ---- the folders inside each layer ------------------------------------------------
here=$(dirname "${BASH_SOURCE[0]}")
bash "$here/check_folder_order.sh" "$src" "$here/folder_order.txt" | sed 's/^/layering: /'
[ "${PIPESTATUS[0]}" -eq 0 ] || bad=1

# ---- symbols of the kernels archive ----------------------------------------------
if [ ! -f "$archive" ]; then
  violation "kernels archive $archive not found"
else
  libm=$(${CC:-cc} -print-file-name=libm.so.6)
  [ -f "$libm" ] || libm=$(ldconfig -p | awk '/libm\.so\.6 / {print $NF; exit}')
  # __cpu_indicator_init, __cpu_model: libgcc's CPU feature detection behind
  # GCC's target_clones (the rod kernels' loops pick AVX2 / AVX-512 at run time).
  allowed=$( { "$nm" -D --defined-only "$libm" | awk '{print $NF}' | sed 's/@.*//';
               printf '%s\n' memset memcpy _GLOBAL_OFFSET_TABLE_ \
                 __cpu_indicator_init __cpu_model; } | sort -u)
  # Undefined in some object and not defined by another object of the archive.
  defined=$("$nm" --defined-only -g "$archive" 2>/dev/null | awk 'NF == 3 {print $3}' | sort -u)
  undefined=$(comm -23 <("$nm" -u "$archive" 2>/dev/null | awk 'NF >= 2 {print $NF}' |
                         sed 's/@.*//' | sort -u) <(printf '%s\n' "$defined"))
  [ -n "$undefined" ] || echo "layering: note: the kernels archive needs no external symbol"
  extra=$(comm -23 <(printf '%s\n' "$undefined" | sed '/^$/d') <(printf '%s\n' "$allowed"))
  if [ -n "$extra" ]; then
    violation "kernels archive needs symbols outside libm/memset/memcpy: $(echo $extra)"
  fi
  # Mutable data (D/B/C/G/S, global or static) means hidden state in the kernels.
  data=$("$nm" --defined-only "$archive" 2>/dev/null | awk 'NF == 3 && $2 ~ /^[DdBbCGgSs]$/ {print $3}' | sort -u)
  if [ -n "$data" ]; then
    violation "kernels archive holds mutable global/static data: $(echo $data)"
  fi
  echo "layering: kernels archive needs: $(echo $undefined)"
fi

if [ $bad -ne 0 ]; then
  echo "layering: FAILED"
  exit 1
fi
echo "layering: ok"
