precision mediump float;
void main() {}
