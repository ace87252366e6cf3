#!/usr/bin/env bash
# check_folder_order.sh SOURCE_DIR [ORDER_FILE]
# The order of the folders inside each layer (issue 23): ORDER_FILE (default
# tests/build/folder_order.txt beside this script) lists per layer its folders
# from low to high,
#     order LAYER: F1 < F2, F3 < F4 ...
# (folders joined by "," are at one level and independent of each other).  A
# source file of LAYER/F may include, by a quoted #include that resolves inside
# LAYER, only headers of its own folder F and of folders below F.  A folder is
# the first path component under the layer (shim_cxx/pc/impls/dd/x.cpp is in
# pc).  Explicit exceptions, each with its reason:
#     except FILE INCLUDED-FILE reason...
# (both relative to SOURCE_DIR).  Prints every violation and every exception
# that no longer matches an include; exits 1 if there is any violation.
set -uo pipefail
src=$1
order=${2:-$(dirname "$0")/folder_order.txt}
bad=0
[ -f "$order" ] || { echo "folder order: $order not found"; exit 1; }

declare -A level        # "layer/folder" -> level
declare -A excepted     # "file included" -> 1
declare -A used         # exceptions that matched
layers=()
while IFS= read -r raw; do
  line=${raw%%#*}
  read -r kw rest <<<"$line"
  case $kw in
    order)
      layer=${rest%%:*}; spec=${rest#*:}
      layers+=("$layer")
      n=0
      IFS='<' read -ra groups <<<"$spec"
      for g in "${groups[@]}"; do
        IFS=',' read -ra folders <<<"$g"
        for f in "${folders[@]}"; do
          f=$(echo $f)
          [ -n "$f" ] && level["$layer/$f"]=$n
        done
        n=$((n + 1))
      done ;;
    except)
      read -r file inc reason <<<"$rest"
      [ -n "${reason:-}" ] || { echo "folder order: exception '$file $inc' gives no reason"; bad=1; }
      excepted["$file $inc"]=1 ;;
    '') ;;
    *) echo "folder order: $order: cannot read '$raw'"; bad=1 ;;
  esac
done <"$order"

# target := the file (relative to src) that a quoted include $1 of the file $2
# (relative to src) names inside its layer $3: beside the file, from the
# layer's root, or from its include/; empty if none.  No process per include.
resolve() {
  local name=$1 from=$2 layer=$3 cand
  target=
  for cand in "${from%/*}/$name" "$layer/$name" "$layer/include/$name"; do
    [ -f "$src/$cand" ] && { normalize "$cand"; return; }
  done
}
# target := the path $1 without "." and "name/.." components.
normalize() {
  local -a in out=()
  local part
  IFS=/ read -ra in <<<"$1"
  for part in "${in[@]}"; do
    case $part in
      . | '') ;;
      ..) [ ${#out[@]} -gt 0 ] && unset 'out[${#out[@]}-1]' ;;
      *) out+=("$part") ;;
    esac
  done
  local IFS=/
  target="${out[*]}"
}

# Every quoted include of the layers' sources, "file:line:name", read by one awk.
quoted_includes() {
  local layer
  for layer in "${layers[@]}"; do
    find "$src/$layer" -type f \( -name '*.c' -o -name '*.h' -o -name '*.cpp' -o -name '*.hpp' \)
  done | sort | tr '\n' '\0' | xargs -0 -r awk '
    FNR == 1 { print FILENAME ":0:" }
    /^[ \t]*#[ \t]*include[ \t]*"/ {
      s = $0; sub(/^[^"]*"/, "", s); sub(/".*/, "", s); print FILENAME ":" FNR ":" s
    }'
}

declare -A warned
while IFS=: read -r file lineno name; do
  rel=${file#"$src"/}
  layer=${rel%%/*}
  sub=${rel#"$layer"/}
  [[ $sub == */* ]] || continue            # a file at the layer's root has no folder
  folder=${sub%%/*}
  mine=${level["$layer/$folder"]:-}
  if [ -z "$mine" ]; then
    if [ -z "${warned[$rel]:-}" ]; then
      echo "folder order: $rel: folder $layer/$folder is not in $(basename "$order")"
      warned[$rel]=1
    fi
    bad=1; continue
  fi
  [ "$lineno" = 0 ] && continue            # the file's own line: no include
  resolve "$name" "$rel" "$layer"
  [ -n "$target" ] || continue             # another layer's header (checked by layering)
  [[ $target == "$layer"/*/* ]] || continue
  tsub=${target#"$layer"/}; tfolder=${tsub%%/*}
  [ "$tfolder" = "$folder" ] && continue
  theirs=${level["$layer/$tfolder"]:-}
  if [ -n "$theirs" ] && [ "$theirs" -lt "$mine" ]; then continue; fi
  if [ -n "${excepted["$rel $target"]:-}" ]; then used["$rel $target"]=1; continue; fi
  if [ -z "$theirs" ]; then
    echo "folder order: $rel:$lineno: includes \"$name\" of $layer/$tfolder, which is not in $(basename "$order")"
  elif [ "$theirs" -eq "$mine" ]; then
    echo "folder order: $rel:$lineno: $layer/$folder includes \"$name\" of $layer/$tfolder, at the same level (independent folders)"
  else
    echo "folder order: $rel:$lineno: $layer/$folder includes \"$name\" of the higher folder $layer/$tfolder"
  fi
  bad=1
done < <(quoted_includes)

for key in "${!excepted[@]}"; do
  [ -n "${used[$key]:-}" ] || echo "folder order: note: the exception '$key' matches no include (remove it)"
done
[ $bad -eq 0 ] && echo "folder order: ok" || echo "folder order: FAILED"
exit $bad
