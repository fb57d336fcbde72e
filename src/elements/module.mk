# Layer: elements. Modules and the objects of the modules each one uses.
MODULES += cfe_element element_interface element_library materials plane_elements
$(OBJDIR)/cfe_element.o: $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/plane_elements.o
$(OBJDIR)/element_interface.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o
$(OBJDIR)/element_library.o: $(OBJDIR)/cfe_element.o $(OBJDIR)/element_interface.o $(OBJDIR)/plane_elements.o
$(OBJDIR)/materials.o: $(OBJDIR)/element_catalogue.o $(OBJDIR)/kinds.o
$(OBJDIR)/plane_elements.o: $(OBJDIR)/element_interface.o $(OBJDIR)/kinds.o $(OBJDIR)/materials.o
