#!/usr/bin/env bash
# Draws every library species at its recommended age in the comparison framing (side and
# oblique views at one scale, 10 cm bars; plantarch compare) into docs/images/gallery/ and
# writes docs/gallery.md (pictures plus the statistics of each plant).
# Usage: bash scripts/make-gallery.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
out=docs/images/gallery
mkdir -p "$out"
page=docs/gallery.md
{
  echo "# Species gallery"
  echo
  echo "Every species of the library at its recommended age (seed 42), made by"
  echo "\`bash scripts/make-gallery.sh\`: a side view along +y and an oblique view, both at one"
  echo "scale with 10 cm bars (\`plantarch compare\`; add \`--reference PICTURE\` to put a"
  echo "photograph or another model's picture in the same framing above). Statistics from"
  echo "\`plantarch build --stats\`; leaves count leaflets."
  echo
  echo "| species | age (d) | height (m) | leaves | shoots | flowers | fruit | triangles |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
} > "$page.tmp"
pictures=""
for file in species/*.xml; do
  name=$(basename "$file" .xml)
  age=$(grep -o '<recommended_age[^>]*default="[0-9.]*"' "$file" | grep -o 'default="[0-9.]*"' | tr -dc '0-9.')
  stats=$(build/plantarch --seed 42 build "$name" --age "$age" --stats)
  build/plantarch --seed 42 --progress never compare "$name" --age "$age" --panel-size 360 \
    -o "$out/$name.png" > /dev/null
  field() { echo "$stats" | grep -o "\"$1\": [0-9.]*" | awk '{print $2}'; }
  echo "| $name | $age | $(field height) | $(field leaves) | $(field shoots) | $(field flowers) | $(field fruit) | $(field triangles) |" >> "$page.tmp"
  pictures+=$'\n'"### $name, $age days"$'\n\n'"![$name at $age days](images/gallery/$name.png)"$'\n'
done
echo "$pictures" >> "$page.tmp"
mv "$page.tmp" "$page"
echo "gallery: $(ls species/*.xml | wc -l) species written to $page"
