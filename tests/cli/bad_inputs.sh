#!/usr/bin/env bash
# bad_inputs.sh HEXCAL DATA: every file of tests/data/bad_inputs through the
# hexcal command that reads it (docs/hardening.md). Each case must exit with
# its code (never a signal), print a message naming the file and matching its
# pattern, and leave no output file behind. The table is one case a line:
#   FILE | EXIT CODE | PATTERN (extended grep, after the file name) | ARGUMENTS
# with @IN@ for the bad file and @OUT@ for an output path in a fresh folder.
# Images are the exception: `measure` records an unreadable image, or one
# without the target, as a row of its (complete) measurements table, so for
# them the output must exist and give the row that status (OUT=table:STATUS).
# SESSION is a session folder with a plan (for acquire's --camera file:).
# No case may let a library's own log lines through to stderr (FFmpeg's
# "[matroska,webm @ 0x...]", OpenCV's "[ WARN:0]"): hexcal --verbose only.
set -u
hexcal=$1 data=$2
corpus=$data/bad_inputs
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

ROBOT="--robot inria-left-hand"
table=$(cat <<'EOF'
poses_empty.csv | 2 | no header line | ik ROBOT --poses @IN@ --out @OUT@
poses_comment_only.csv | 2 | no header line | ik ROBOT --poses @IN@ --out @OUT@
poses_header_only.csv | 2 | no poses | ik ROBOT --poses @IN@ --out @OUT@
poses_missing_header.csv | 2 | :1: no header: column 1 is the number '0', and the first line must name the columns | ik ROBOT --poses @IN@ --out @OUT@
poses_duplicate_header.csv | 2 | :1: duplicate column 'z' | ik ROBOT --poses @IN@ --out @OUT@
poses_missing_column.csv | 2 | missing column 'q3' | ik ROBOT --poses @IN@ --out @OUT@
poses_short_row.csv | 2 | :3: 5 columns, header has 6 | ik ROBOT --poses @IN@ --out @OUT@
poses_long_row.csv | 2 | :3: 7 columns, header has 6 | ik ROBOT --poses @IN@ --out @OUT@
poses_truncated.csv | 2 | :3: 5 columns, header has 6 | ik ROBOT --poses @IN@ --out @OUT@
poses_nan.csv | 2 | :3: column 'y': 'nan' is not a finite number | ik ROBOT --poses @IN@ --out @OUT@
poses_inf.csv | 2 | :3: column 'z': 'inf' is not a finite number | ik ROBOT --poses @IN@ --out @OUT@
poses_huge.csv | 2 | :3: column 'z': '1e400' is not a finite number | ik ROBOT --poses @IN@ --out @OUT@
poses_text.csv | 2 | :3: column 'z': 'abc' is not a finite number | ik ROBOT --poses @IN@ --out @OUT@
poses_unterminated_quote.csv | 2 | :2: field 6: quoted field has no closing quote | ik ROBOT --poses @IN@ --out @OUT@
poses_binary.csv | 2 | missing column 'x' | ik ROBOT --poses @IN@ --out @OUT@
poses_nan.csv | 2 | :3: column 'y': 'nan' is not a finite number | plan ROBOT --poses 7 --candidates @IN@ --out @OUT@
poses_empty.csv | 2 | no header line | plan ROBOT --poses 7 --init @IN@ --out @OUT@
poses_inf.csv | 2 | :3: column 'z': 'inf' is not a finite number | render --poses @IN@ --out @OUT@
measurements_empty.csv | 2 | no header line | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_missing_leg.csv | 2 | missing column 'L6' | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_duplicate_header.csv | 2 | :1: duplicate column 'L6' | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_short_row.csv | 2 | :2: 11 columns, header has 12 | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_inf.csv | 2 | :2: column 'L4': '-inf' is not a finite number | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_huge.csv | 2 | :2: column 'L5': '1e999' is not a finite number | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_missing_header.csv | 2 | :1: no header: column 1 is the number | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_fewer_than_parameters.csv | 2 | at least 7 measurements \(7 parameters per leg\), got 6 | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_singular_poses.csv | 1 | degenerate pose set: leg 1's identification Jacobian has rank 1 of 7 | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_camera_poses.csv | 2 | missing column 'L1'.*; this is a table of camera poses .*use `hexcal calibrate --session DIR` | calibrate ROBOT --measurements @IN@ --out @OUT@
measurements_leg_readings.csv | 2 | missing column 'x'.*; this is a session's leg readings .*`hexcal calibrate --session DIR` | validate ROBOT --measurements @IN@
measurements_wrong_unit.csv | 2 | readings look like mm, the robot .inria-left-hand. is in cm: measurement 1: L1 = 22.58914313 is far outside the stroke \[0, 3.5\] cm | calibrate ROBOT --measurements @IN@ --out @OUT@
poses_unreachable.csv | 2 | none of its 4 poses satisfies the robot and measurement constraints | plan ROBOT --poses 7 --candidates @IN@ --out @OUT@
settings_empty.yaml | 2 | expected a mapping at the top level | plan ROBOT --settings @IN@ --out @OUT@
settings_top_level_list.yaml | 2 | expected a mapping at the top level | plan ROBOT --settings @IN@ --out @OUT@
settings_syntax_error.yaml | 2 | error at line 2, column 1 | plan ROBOT --settings @IN@ --out @OUT@
settings_nan.yaml | 2 | noise.position: expected a finite number | plan ROBOT --settings @IN@ --out @OUT@
settings_negative_noise.yaml | 2 | noise.position: must be at least 0 | plan ROBOT --settings @IN@ --out @OUT@
settings_list_key.yaml | 2 | top level: a key that is not a name | plan ROBOT --settings @IN@ --out @OUT@
settings_noise_list.yaml | 2 | noise: expected a mapping \{position, angle_deg, leg\} | plan ROBOT --settings @IN@ --out @OUT@
settings_duplicate_key.yaml | 2 | noise.position: duplicate key \(lines 2 and 4\) | plan ROBOT --settings @IN@ --out @OUT@
settings_seed_rounded.yaml | 2 | planner.seed: must be at most 9007199254740992, got 9007199254740993 | plan ROBOT --settings @IN@ --out @OUT@
settings_integer_exponent.yaml | 2 | planner.tabu: expected a whole number in decimal digits, got '1e1' | plan ROBOT --settings @IN@ --out @OUT@
settings_camera_short_vector.yaml | 2 | measurement constraints need all three | plan ROBOT --settings @IN@ --out @OUT@
target_empty.yaml | 2 | top level: expected a mapping | target print --target @IN@ --out @OUT@.pdf
target_syntax_error.yaml | 2 | YAML syntax error at line 3 | target print --target @IN@ --out @OUT@.pdf
target_truncated.yaml | 2 | tag_si: unknown key | target print --target @IN@ --out @OUT@.pdf
target_nan_size.yaml | 2 | tag_size: '.nan' is not a finite number | target print --target @IN@ --out @OUT@.pdf
target_huge_grid.yaml | 2 | exceed the 587 tags of tag36h11 | target print --target @IN@ --out @OUT@.pdf
target_unknown_family.yaml | 2 | family: 'tag99h99' is not supported | target print --target @IN@ --out @OUT@.pdf
target_wrong_unit.yaml | 2 | length_unit: expected mm, cm or m | target print --target @IN@ --out @OUT@.pdf
target_tag_size_huge.yaml | 2 | tag_size: 1e\+300 mm is outside \[0.1, 10000\] mm | target print --target @IN@ --out @OUT@.pdf
target_tag_size_tiny.yaml | 2 | tag_size: 1e-300 mm is outside \[0.1, 10000\] mm | target print --target @IN@ --out @OUT@.pdf
target_duplicate_key.yaml | 2 | tag_size: duplicate key \(lines 5 and 7\) | target print --target @IN@ --out @OUT@.pdf
target_nan_size.yaml | 2 | tag_size: '.nan' is not a finite number | measure --camera sim-4.2mm-1024x768 --target @IN@ --images IMAGE --out @OUT@
camera_empty.yaml | 2 | empty file | measure --camera @IN@ --images IMAGE --out @OUT@
camera_garbage.yaml | 2 | expected a camera mapping | measure --camera @IN@ --images IMAGE --out @OUT@
camera_truncated.yaml | 2 | YAML syntax error at line 9 | measure --camera @IN@ --images IMAGE --out @OUT@
camera_nan_focal.yaml | 2 | camera_matrix.data: expected numbers, found '.nan' | measure --camera @IN@ --images IMAGE --out @OUT@
camera_wrong_matrix_size.yaml | 2 | camera_matrix: expected 9 numbers \(3 x 3\), found 4 | measure --camera @IN@ --images IMAGE --out @OUT@
camera_ros_missing_k.yaml | 2 | camera_matrix.data: expected a list of numbers | measure --camera @IN@ --images IMAGE --out @OUT@
camera_huge_matrix.yaml | 2 | camera_matrix: 2147483647 x 8 is not a camera matrix | measure --camera @IN@ --images IMAGE --out @OUT@
camera_opencv_loop.yaml | 2 | image_width: missing | measure --camera @IN@ --images IMAGE --out @OUT@
camera_parser_exception.yaml | 2 | YAML syntax error at line 9 | measure --camera @IN@ --images IMAGE --out @OUT@
camera_duplicate_key.yaml | 2 | camera_matrix.rows: duplicate key \(lines 6 and 8\) | measure --camera @IN@ --images IMAGE --out @OUT@
camera_huge_resolution.yaml | 2 | image size 1000000 x 1000000: over the 150-megapixel limit | measure --camera @IN@ --images IMAGE --out @OUT@
camera_camchain_cam1_only.yaml | 2 | cam1: a Kalibr camchain without cam0; hexcal reads cam0 | measure --camera @IN@ --images IMAGE --out @OUT@
camera_focal_huge.yaml | 2 | fx = 1e\+300 px is outside \[0.01, 10000000\] px | measure --camera @IN@ --images IMAGE --out @OUT@
camera_principal_point_far.yaml | 2 | cx = -5000 px is outside \[-1024, 2048\] px | measure --camera @IN@ --images IMAGE --out @OUT@
camera_k1_huge.yaml | 2 | distortion coefficient 1 = 1e\+300 is outside \[-1000000, 1000000\] | measure --camera @IN@ --images IMAGE --out @OUT@
camera_zero_size.yaml | 2 | image size 0 x 768: must be positive | render --camera @IN@ --poses POSES --out @OUT@
image_empty.png | 1 | empty file | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_header_only.png | 1 | truncated PNG \(no IEND chunk\) | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_truncated.png | 1 | truncated PNG \(no IEND chunk\) | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_huge_header.png | 1 | 30000 x 30000 pixels is over the 150-megapixel limit | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_truncated.jpg | 1 | truncated JPEG \(no end-of-image marker\) | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_bad_crc.png | 1 | cannot decode: corrupt, truncated or not an image | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_garbage.png | 1 | cannot decode: not a PNG, JPEG or TIFF file | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_dicom_assert.png | 1 | cannot decode: not a PNG, JPEG or TIFF file | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:unreadable
image_no_target.png | 2 | no_target: no tag of the target found | measure --camera sim-4.2mm-1024x768 --images @IN@ --out @OUT@ OUT=table:no_target
image_no_target.png | 2 | : 0 tags\); check that these are images of the board | intrinsics --images @IN@ --out @OUT@.yaml
video_corrupt.mkv | 2 | not a video OpenCV can read | acquire --session SESSION --controller sim --camera file:@IN@
EOF
)

session=$work/session
"$hexcal" session init "$session" $ROBOT --camera sim-4.2mm-1024x768 --target aprilgrid-6x6 >/dev/null || exit 1
cp "$data/poses/inria_sample.csv" "$session/plan.csv"
library_lines='^\[( ?(WARN|INFO|ERROR)|[a-z0-9_,]+ @ 0x)|GStreamer-|Aravis-|moov atom'

cases=0 failures=0
declare -A covered=()
while IFS='|' read -r file code pattern args; do
  file=$(echo $file) code=$(echo $code) pattern=$(echo "$pattern" | sed 's/^ *//; s/ *$//')
  [ -n "$file" ] || continue
  cases=$((cases + 1))
  covered[$file]=1
  dir=$work/case$cases
  mkdir "$dir"
  out=$dir/out
  expect_status=""
  argv=()
  for word in $args; do
    case $word in
      ROBOT) argv+=($ROBOT) ;;
      IMAGE) argv+=("$corpus/image_garbage.png") ;;
      POSES) argv+=("$data/poses/vision_views.csv") ;;
      SESSION) argv+=("$session") ;;
      OUT=table:*) expect_status=${word#OUT=table:} ;;
      *) word=${word//@IN@/$corpus/$file}; argv+=("${word//@OUT@/$out}") ;;
    esac
  done
  output=$("$hexcal" "${argv[@]}" 2>&1)
  got=$?
  problem=""
  if [ "$got" -ge 128 ]; then
    problem="killed by signal $((got - 128))"
  elif [ "$got" != "$code" ]; then
    problem="exit code $got, expected $code"
  elif ! grep -Eq -- "$file.*$pattern" <<<"$output"; then
    problem="output does not name the file and match /$pattern/"
  elif grep -Eq -- "$library_lines" <<<"$output"; then
    problem="a library's log lines on stderr"
  elif [ -n "$expect_status" ]; then
    grep -q "$file,.*,$expect_status," "$out" 2>/dev/null || problem="no '$expect_status' row for it in $out"
  elif compgen -G "$out*" >/dev/null || compgen -G "$dir/.out*" >/dev/null; then
    problem="left output behind: $(ls -A "$dir")"
  fi
  if [ -n "$problem" ]; then
    failures=$((failures + 1))
    echo "FAIL: $file: $problem: hexcal ${argv[*]}"
    echo "$output" | head -5
  fi
done <<<"$table"

# Every corpus file must be in the table.
for path in "$corpus"/*; do
  name=$(basename "$path")
  if [ -z "${covered[$name]:-}" ]; then
    failures=$((failures + 1))
    echo "FAIL: $name is in $corpus but not in the table"
  fi
done
echo "$cases cases, ${#covered[@]} files, $failures failures"
[ "$failures" = 0 ]
