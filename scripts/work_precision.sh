#!/usr/bin/env bash
# The work-precision report (doc/error_vs_runtime.md): builds, runs mbk_work_precision,
# writes doc/work_precision/{work_precision.csv,work_precision.md,work_precision.png} and puts the
# table into doc/error_vs_runtime.md between its work-precision markers. --quick: fewer states and repetitions.
source "$(dirname "$0")/common.sh"
MBK_PACKAGES+=(python3-matplotlib)
mbk_install_deps
mbk_build mbk_work_precision
out="$MBK_SRC/doc/work_precision"
mkdir -p "$out"
"$MBK_WS/devel/lib/mb_kinematics/mbk_work_precision" --out "$out" "$@"
/usr/bin/python3 "$MBK_SRC/scripts/plot_work_precision.py" "$out/work_precision.csv" "$out/work_precision.png"
/usr/bin/python3 - "$MBK_SRC/doc/error_vs_runtime.md" "$out/work_precision.md" <<'PY'
import sys
readme, table = sys.argv[1], open(sys.argv[2]).read()
text = open(readme).read()
begin, end = "<!-- work-precision:begin -->", "<!-- work-precision:end -->"
if begin in text and end in text:
    head, rest = text.split(begin, 1)
    text = head + begin + "\n" + table + rest[rest.index(end):]
    open(readme, "w").write(text)
PY
echo "wrote $out/work_precision.{csv,md,png} and the table of doc/error_vs_runtime.md"
