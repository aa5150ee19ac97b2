// Pass part "shadow-caster" (fragment stage): depth only; the object's material is not needed,
// so the shadow-map pass leaves the object's fragment parts out of its programs.
void main() {}
